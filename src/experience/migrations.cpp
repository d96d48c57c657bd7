// The migrations in migrations/*.sql, embedded in the binary.
//
// Kept by hand, byte for byte equal to the files: a unit test
// (test_store_schema.cpp) compares each entry with its file. To add a
// migration: write migrations/NNNN_name.sql, paste it here as the next
// entry, and update schema/schema.sql.
#include "earc/experience/schema.hpp"

#include <iterator>

namespace earc::exp {

namespace {

constexpr Migration kMigrations[] = {
    {1, "0001_create_experiences.sql", R"sql(-- Migration 1: the experiences table.
-- One row is one solved subproblem in canonical form (see
-- include/earc/experience/keys.hpp): its class (kind, robot_count,
-- signature, base_class), its start/goal key and every robot's path.
PRAGMA application_id = 1161908803;  -- 0x45415243, "EARC"

CREATE TABLE experiences (
  -- AUTOINCREMENT: ids are never reused, so "rows with id > max loaded"
  -- is exactly the set of rows another process inserted since.
  id          INTEGER PRIMARY KEY AUTOINCREMENT,
  kind        TEXT    NOT NULL CHECK (kind IN ('mobile', 'manipulator')),
  robot_count INTEGER NOT NULL CHECK (robot_count BETWEEN 1 AND 64),
  -- RobotModel::geometrySignature of each robot, canonical order, '|'-joined.
  signature   TEXT    NOT NULL,
  -- Manipulators: relative base transform class; '' for mobile robots.
  base_class  TEXT    NOT NULL,
  -- Start/goal key: little-endian IEEE doubles, no header (the class fixes
  -- its length).
  key         BLOB    NOT NULL,
  -- Every robot's time-stamped path, canonical frame and order, as one
  -- blob with a header (include/earc/experience/path_blob.hpp).
  paths       BLOB    NOT NULL,
  -- Sum over robots of the path length in steps.
  cost        REAL    NOT NULL,
  source      TEXT    NOT NULL CHECK (source IN ('build', 'planner', 'import')),
  -- Unix time in seconds (UTC).
  created_at  INTEGER NOT NULL
);

CREATE INDEX experiences_by_class ON experiences (kind, robot_count, signature, base_class);
)sql"},
    {2, "0002_usage_and_sessions.sql", R"sql(-- Migration 2: learning across sessions.
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
)sql"},
    {3, "0003_key_scan_index.sql", R"sql(-- Migration 3: a covering index for loading the k-d trees.
-- Opening a store reads every row's class and key. Path blobs share the
-- table's pages with them, so without this index that scan reads every path
-- too; with it, only the index. The id comes first so that loading the rows
-- inserted since a known id is a range scan.
CREATE INDEX experiences_keys ON experiences (id, kind, robot_count, signature, base_class, key);
)sql"},
    {4, "0004_made_by.sql", R"sql(-- Migration 4: the build that made each row.
-- The earc build that solved the subproblem (what `earc-db --version`
-- prints, e.g. "0.1.0+6030a7c"), kept as it is through export and import,
-- so that a curator can find and drop what one build stored. Rows stored
-- before this migration have '' (not known).
ALTER TABLE experiences ADD COLUMN made_by TEXT NOT NULL DEFAULT '';
)sql"},
    {5, "0005_history.sql", R"sql(-- Migration 5: what was done to the file, and by which build.
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
)sql"},
    {6, "0006_path_blob_checksums.sql", R"sql(-- Migration 6: path blobs that carry a checksum.
-- No table changes. From this version on the paths column may hold path
-- blobs of format version 3 (include/earc/experience/path_blob.hpp): a
-- CRC-32C of the blob at its end, so that a changed byte inside a stored
-- path, which SQLite's checks cannot see, is found by earc-db verify and
-- refused on reading. An earc of schema version 5 cannot read them: it
-- refuses the file as newer, at once, instead of skipping its rows one by
-- one. Rows stored before keep their blobs (earc-db curate --compact
-- rewrites them).
)sql"},
};

}  // namespace

std::span<const Migration> migrations() { return kMigrations; }

int currentSchemaVersion() { return static_cast<int>(std::size(kMigrations)); }

}  // namespace earc::exp
