-- Migration 2: learning across sessions.
-- Usage counters (recordUse), the time the solver took, the session that
-- created a row, and a small key/value table with the session counter and
-- a deletion counter that tells other processes to reload their index.
ALTER TABLE experiences ADD COLUMN solve_time_s    REAL    NOT NULL DEFAULT 0;
ALTER TABLE experiences ADD COLUMN retrieved_count INTEGER NOT NULL DEFAULT 0;
ALTER TABLE experiences ADD COLUMN succeeded_count INTEGER NOT NULL DEFAULT 0;
ALTER TABLE experiences ADD COLUMN created_session INTEGER NOT NULL DEFAULT 0;

CREATE TABLE store_meta (
  name  TEXT PRIMARY KEY,
  value INTEGER NOT NULL
) WITHOUT ROWID;

-- sessions: read-write opens that counted as a planning session.
-- deletions: rows deleted so far (by any program, through the trigger).
INSERT INTO store_meta (name, value) VALUES ('sessions', 0), ('deletions', 0);

CREATE TRIGGER experiences_count_deletions AFTER DELETE ON experiences
BEGIN
  UPDATE store_meta SET value = value + 1 WHERE name = 'deletions';
END;
