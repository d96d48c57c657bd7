-- PostgreSQL migration 2: what was done to the store, and by which build.
-- As the SQLite file's history (migrations/0005_history.sql): a line when
-- the store is created or migrated, and one per open that then added or
-- removed rows, brought up to date inside each change's transaction. A
-- writer whose connection broke during COMMIT reads its line (by token)
-- to learn whether the COMMIT went through.
CREATE TABLE earc.history (
  id           bigint GENERATED ALWAYS AS IDENTITY PRIMARY KEY,
  token        bigint NOT NULL UNIQUE,
  at           bigint NOT NULL,
  program      text   NOT NULL,
  operation    text   NOT NULL CHECK (operation IN ('create', 'migrate', 'build', 'import', 'curate', 'learn')),
  detail       text   NOT NULL DEFAULT '',
  rows_added   bigint NOT NULL DEFAULT 0,
  rows_removed bigint NOT NULL DEFAULT 0
);
