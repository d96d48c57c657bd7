-- Results migration 7: how the run grew its Lightning databases
-- (--lightning-problems, else --lightning-problems-per-robot; and
-- --lightning-problem-time-limit), on each lightning trial: a database grown
-- from other problems or under another limit is another experiment, which a
-- resumed run must not pool with the first. NULL on other methods' trials
-- and on every trial recorded before it.
ALTER TABLE trials ADD COLUMN lightning_problems INTEGER;
ALTER TABLE trials ADD COLUMN lightning_problems_per_robot INTEGER;
ALTER TABLE trials ADD COLUMN lightning_problem_time_limit_s REAL;
