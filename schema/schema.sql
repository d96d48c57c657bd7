-- The experience database schema, current version (6).
--
-- This file documents the schema; the program never runs it. Databases are
-- created and upgraded only by the numbered migrations in ../migrations/,
-- embedded in the binary by the build (tools/embed_migrations.cmake), each
-- applied in its own BEGIN IMMEDIATE ... COMMIT with its user_version bump.
-- A unit test (test_store_schema.cpp) checks that this file produces exactly
-- the tables, columns, indexes and triggers the migrations produce.
--
-- Identification: application_id 0x45415243 ("EARC"); user_version is the
-- schema version. A program refuses files with another application_id and
-- files whose user_version is newer than its own.
PRAGMA application_id = 1161908803;
PRAGMA user_version = 6;

-- One row per solved subproblem, in canonical form
-- (include/earc/experience/keys.hpp).
CREATE TABLE experiences (
  id              INTEGER PRIMARY KEY AUTOINCREMENT,  -- never reused
  kind            TEXT    NOT NULL CHECK (kind IN ('mobile', 'manipulator')),
  robot_count     INTEGER NOT NULL CHECK (robot_count BETWEEN 1 AND 64),
  signature       TEXT    NOT NULL,  -- geometry signatures, canonical order, '|'-joined
  base_class      TEXT    NOT NULL,  -- arms: relative base transform class; mobile: ''
  key             BLOB    NOT NULL,  -- start/goal key, little-endian doubles
  paths           BLOB    NOT NULL,  -- all paths, header + body (path_blob.hpp; version 3: keyframes, differences, CRC-32)
  cost            REAL    NOT NULL,  -- sum over robots of path length in steps
  source          TEXT    NOT NULL CHECK (source IN ('build', 'planner', 'import')),
  created_at      INTEGER NOT NULL,  -- Unix seconds, UTC
  solve_time_s    REAL    NOT NULL DEFAULT 0,  -- time the solver took (0: unknown)
  retrieved_count INTEGER NOT NULL DEFAULT 0,  -- times handed to a planner
  succeeded_count INTEGER NOT NULL DEFAULT 0,  -- times it resolved the subproblem
  created_session INTEGER NOT NULL DEFAULT 0,  -- store_meta 'sessions' when inserted
  made_by         TEXT    NOT NULL DEFAULT ''  -- earc build that solved it ('': before version 4)
);

-- Index loading and per-class counts read by class.
CREATE INDEX experiences_by_class ON experiences (kind, robot_count, signature, base_class);

-- Loading the k-d trees reads only this index, never the path blobs; id
-- first, so "rows since id N" is a range scan.
CREATE INDEX experiences_keys ON experiences (id, kind, robot_count, signature, base_class, key);

-- Counters: 'sessions' (planning sessions opened read-write) and
-- 'deletions' (rows deleted; a change makes other processes reload).
CREATE TABLE store_meta (
  name  TEXT PRIMARY KEY,
  value INTEGER NOT NULL
) WITHOUT ROWID;

INSERT INTO store_meta (name, value) VALUES ('sessions', 0), ('deletions', 0);

CREATE TRIGGER experiences_count_deletions AFTER DELETE ON experiences
BEGIN
  UPDATE store_meta SET value = value + 1 WHERE name = 'deletions';
END;

-- What was done to the file, and by which build (include/earc/experience/
-- history.hpp): one line per open that changed it, kept up to date in the
-- same transaction as each change it counts.
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
