-- Results migration 8: on each earc and lightning trial whether its run let
-- the databases learn (--learn, 1 or 0), and on each earc trial the E-ARC
-- database it used (as the run was given it or made it) and where that
-- database's history stood when the run began (the token of its last line,
-- NULL for a database without one): a resumed run on another database, or
-- with learning switched, must not pool its trials with the first. NULL
-- elsewhere and on every trial recorded before it.
ALTER TABLE trials ADD COLUMN learn INTEGER;
ALTER TABLE trials ADD COLUMN earc_db TEXT;
ALTER TABLE trials ADD COLUMN earc_db_state INTEGER;
