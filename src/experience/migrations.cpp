// The migrations in migrations/*.sql, embedded in the binary from the
// files themselves at build time (tools/embed_migrations.cmake). To add a
// migration: write migrations/NNNN_name.sql and update schema/schema.sql.
#include "earc/experience/schema.hpp"

#include <iterator>

namespace earc::exp {

namespace {

constexpr Migration kMigrations[] = {
#include "migrations/store.inc"
};

}  // namespace

std::span<const Migration> migrations() { return kMigrations; }

int currentSchemaVersion() { return static_cast<int>(std::size(kMigrations)); }

}  // namespace earc::exp
