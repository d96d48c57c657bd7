-- Results migration 2: how many trials the run had at once (--jobs).
-- Side by side, trials disturb each other's timings, and how depends on the
-- order (see runner.cpp). NULL for trials recorded before it.
ALTER TABLE trials ADD COLUMN jobs INTEGER;
