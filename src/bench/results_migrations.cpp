// The migrations in migrations/results/*.sql, embedded in the binary from
// the files themselves at build time (tools/embed_migrations.cmake). To add
// a migration: write migrations/results/NNNN_name.sql, raise
// kResultsSchemaVersion and read its columns (results_db.cpp,
// kAddedTrialColumns).
#include "earc/bench/results_migrations.hpp"

#include <iterator>

#include "earc/bench/results_db.hpp"

namespace earc::bench {

namespace {

constexpr ResultsMigration kResultsMigrations[] = {
#include "migrations/results.inc"
};
static_assert(std::size(kResultsMigrations) == kResultsSchemaVersion, "a migration for every version");

}  // namespace

std::span<const ResultsMigration> resultsMigrations() { return kResultsMigrations; }

}  // namespace earc::bench
