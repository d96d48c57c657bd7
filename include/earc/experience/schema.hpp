// The experience database's identity and schema versions.
//
// The schema is documented in schema/schema.sql; it is created and upgraded
// only by the numbered migrations in migrations/NNNN_*.sql, whose text the
// build embeds from the files (tools/embed_migrations.cmake).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "earc/experience/sqlite.hpp"
#include "earc/io/input_error.hpp"

namespace earc::exp {

// PRAGMA application_id of every earc experience database: "EARC".
inline constexpr std::int64_t kApplicationId = 0x45415243;

struct Migration {
  int version;                // user_version after this step
  std::string_view name;      // file name in migrations/
  std::string_view sql;       // the file's text
};

// All migrations, in order; migrations()[i].version == i + 1.
std::span<const Migration> migrations();

// The schema version this program writes and reads: the last migration.
int currentSchemaVersion();

// The last schema version that changed the experiences table's columns.
// An export says this version (or its file's, when older): its rows read
// the same in every program since, whatever later migrations added.
inline constexpr int kExperienceRowsSchemaVersion = 4;

// Checks that the connection's file is an earc database this program can
// use (or an empty file): ForeignDatabaseError for another application's
// SQLite file or not a SQLite file at all, SchemaVersionError for a newer
// schema. Returns the file's schema version (0 for an empty file).
int checkIdentity(Connection& db);

// A file with no earc database in it yet (0 bytes, or SQLite without
// tables): commands that write make it one, commands that only read refuse
// it with this error, in one wording: "FILE: empty file (0 bytes), not an
// earc database yet" (`what`: the kind of database, for earc-bench's
// results).
InputError notYetADatabase(const std::string& path, std::string_view what = "an earc database");

// Refuses, before SQLite sees it, a database file that a command only
// reads (inspect, verify, export, import sources, curate's inputs) and that
// is missing ("FILE: no such file"), a directory, or, unless may_be_empty
// (a command that writes it), 0 bytes (notYetADatabase).
void requireDatabaseFile(const std::string& path, bool may_be_empty = false);

// Brings the file up to `target` (default: current), one migration per
// BEGIN IMMEDIATE transaction with its user_version bump, so a crash
// mid-way leaves the previous version intact; a new (empty) file gets every
// migration in one such transaction. Safe against another process
// migrating the same file at the same time. Returns the version reached.
int migrate(Connection& db, int target = -1);

}  // namespace earc::exp
