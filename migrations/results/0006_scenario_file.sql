-- Results migration 6: the path of a scenario file's trial (suite
-- kFilesSuite, earc-bench run FILE...) as the run was given it: its suite,
-- robot count and trial number say only where among the files it came.
-- NULL for a suite's trials, and for every trial recorded before it.
ALTER TABLE trials ADD COLUMN scenario_file TEXT;
