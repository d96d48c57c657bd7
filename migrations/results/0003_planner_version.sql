-- Results migration 3: the build that planned the trial (the earc_version
-- its solution reported), so that every figure can be traced to its code.
-- NULL for trials recorded before it and for planners that do not say.
ALTER TABLE trials ADD COLUMN planner_version TEXT;
