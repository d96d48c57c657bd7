-- Results migration 9: what the crowd suites report beside the time: the
-- sum-of-costs lower bound of the trial's scenario (the sum of its robots'
-- own shortest paths in steps, bench/crowds.hpp), and the solution's
-- stats.refine (earc-plan --refine) when it has them, so that cost is
-- compared with the bound. NULL otherwise and on every trial recorded
-- before it.
ALTER TABLE trials ADD COLUMN lower_bound INTEGER;
ALTER TABLE trials ADD COLUMN refine_first_time_s REAL;
ALTER TABLE trials ADD COLUMN refine_first_sum_of_costs INTEGER;
ALTER TABLE trials ADD COLUMN refine_final_sum_of_costs INTEGER;
ALTER TABLE trials ADD COLUMN refine_final_makespan INTEGER;
