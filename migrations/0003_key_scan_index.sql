-- Migration 3: a covering index for loading the k-d trees.
-- Opening a store reads every row's class and key. Path blobs share the
-- table's pages with them, so without this index that scan reads every path
-- too; with it, only the index. The id comes first so that loading the rows
-- inserted since a known id is a range scan.
CREATE INDEX experiences_keys ON experiences (id, kind, robot_count, signature, base_class, key);
