-- Results migration 5: the arguments the run added to the trial's
-- `earc-plan plan` (--method-arg), as a JSON array of strings: E-ARC with
-- --db-k=5 is another experiment than E-ARC. NULL for none, as for every
-- trial recorded before it. All trials of one method in a file have the
-- same, so that table, export and plot never pool two settings in a cell.
ALTER TABLE trials ADD COLUMN planner_args TEXT;
