// The PostgreSQL experience store's schema: its numbered migrations
// (migrations/postgresql/NNNN_*.sql, embedded by the build from the files),
// its identity check, and reading and writing whole rows and
// history lines. Everything lives in the database's schema "earc".
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "earc/experience/experience.hpp"
#include "earc/experience/history.hpp"
#include "earc/experience/pg_connection.hpp"
#include "earc/experience/schema.hpp"

namespace earc::exp {

// All PostgreSQL migrations, in order; pgMigrations()[i].version == i + 1.
std::span<const Migration> pgMigrations();
int pgCurrentSchemaVersion();

// The advisory lock every write transaction takes first (pg_advisory_xact_lock):
// writers one at a time, as SQLite's BEGIN IMMEDIATE makes them.
inline constexpr std::int64_t kPgWriteLock = 0x45415243;

// The store's schema version, 0 for a database without tables. Reads only;
// throws ForeignDatabaseError (tables, no earc schema), SchemaVersionError.
int pgCheckIdentity(PgConnection& db);

// Brings the database up to the current version, one migration per
// transaction under kPgWriteLock (its version row updated in it); safe
// against others migrating at once. Returns the version reached.
int pgMigrate(PgConnection& db, int target = -1);

// "SELECT <all columns> FROM earc.experiences" (the order readPgExperience
// reads); append WHERE / ORDER BY.
std::string pgSelectExperiencesSql();
// The rows with an id above $1 in that column order, then the store's
// deletions count as column kPgRowColumns; one row of NULLs and the count
// when there are none.
inline constexpr int kPgRowColumns = 15;
std::string pgSelectTailWithDeletionsSql();
// Row `row` of such a result, checked as readExperience checks. Throws
// CorruptRowError.
Experience readPgExperience(const PgResult& r, int row);

// "INSERT ... VALUES (...), ... RETURNING id" for `rows` rows, and one
// row's parameters (every column but id), appended in row order.
inline constexpr int kPgInsertColumns = 14;
std::string pgInsertExperiencesSql(std::size_t rows);
PgParams pgExperienceParams(const Experience& e);

// Every row in `order` (an ORDER BY clause) in one snapshot: the count to
// onCount, each readable row to onRow, each damaged one to onDamaged
// (rethrown when not given).
void pgForEachExperience(PgConnection& db, const std::string& order,
                         const std::function<void(std::int64_t)>& onCount,
                         const std::function<void(Experience&&)>& onRow,
                         const std::function<void(const CorruptRowError&)>& onDamaged = {});

// Inside a write transaction: counts rows on the writer's history line
// (HistoryWriter::record's contract).
void pgRecordHistory(PgConnection& db, const HistoryWriter& writer, std::int64_t added, std::int64_t removed,
                     bool even_if_unchanged = false);
// The rows added on the writer's line so far (0 without a line).
std::int64_t pgHistoryRowsAdded(PgConnection& db, const HistoryWriter& writer);
HistoryTail pgReadHistory(PgConnection& db, int limit);

}  // namespace earc::exp
