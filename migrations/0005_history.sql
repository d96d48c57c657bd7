-- Migration 5: what was done to the file, and by which build.
-- A line when the file is created or migrated, and one per open that then
-- added or removed rows: built, imported, curated, or learned in a planning
-- session. The line is written with the open's first change and brought up
-- to date in the same transaction as each later one, so after a crash it
-- still counts exactly the rows that were committed.
CREATE TABLE history (
  id           INTEGER PRIMARY KEY AUTOINCREMENT,  -- order of first change
  token        INTEGER NOT NULL,  -- random per open: the line it keeps up to date
  at           INTEGER NOT NULL,  -- Unix seconds, UTC, of the first change
  program      TEXT    NOT NULL,  -- earc build, as `earc-db --version` prints it
  operation    TEXT    NOT NULL CHECK (operation IN ('create', 'migrate', 'build', 'import', 'curate', 'learn')),
  detail       TEXT    NOT NULL DEFAULT '',  -- for people: options, sources, session
  rows_added   INTEGER NOT NULL DEFAULT 0,
  rows_removed INTEGER NOT NULL DEFAULT 0
);

-- Each change finds its open's line by token.
CREATE UNIQUE INDEX history_by_token ON history (token);
