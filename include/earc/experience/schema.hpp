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

// The file's schema version (0: an empty file). Throws ForeignDatabaseError
// for another application's file or not SQLite, SchemaVersionError for a
// newer schema.
int checkIdentity(Connection& db);

// The error for a file with no database in it yet (0 bytes, or SQLite
// without tables), refused by a command that only reads it; `what`: the
// kind of database named.
InputError notYetADatabase(const std::string& path, std::string_view what = "an earc database");

// Throws InputError, before SQLite sees it, for a database file that is
// missing, a directory, or 0 bytes unless may_be_empty (notYetADatabase).
// For the commands that only read a file.
void requireDatabaseFile(const std::string& path, bool may_be_empty = false);

// Brings the file up to `target` (default: current), a transaction per
// migration; returns the version reached. Safe against a crash mid-way and
// against another process migrating the same file at once.
int migrate(Connection& db, int target = -1);

}  // namespace earc::exp
