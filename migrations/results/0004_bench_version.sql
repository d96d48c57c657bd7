-- Results migration 4: the earc-bench build that ran and timed the trial
-- (its --version). How trials are run changes their timings too, and
-- --plan-program plans with another build than the one timing. NULL for
-- trials recorded before it.
ALTER TABLE trials ADD COLUMN bench_version TEXT;
