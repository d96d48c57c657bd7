-- Migration 1: the experiences table.
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
