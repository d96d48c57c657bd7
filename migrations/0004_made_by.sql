-- Migration 4: the build that made each row.
-- The earc build that solved the subproblem (what `earc-db --version`
-- prints, e.g. "0.1.0+6030a7c"), kept as it is through export and import,
-- so that a curator can find and drop what one build stored. Rows stored
-- before this migration have '' (not known).
ALTER TABLE experiences ADD COLUMN made_by TEXT NOT NULL DEFAULT '';
