// The results database's migrations: migrations/results/*.sql, embedded in
// the binary by the build from the files (tools/embed_migrations.cmake).
#pragma once

#include <span>
#include <string_view>

namespace earc::bench {

struct ResultsMigration {
  int version;            // user_version after this step
  std::string_view name;  // file name in migrations/results/
  std::string_view sql;   // the file's text
};

// All migrations, in order; resultsMigrations()[i].version == i + 1, the
// last being kResultsSchemaVersion.
std::span<const ResultsMigration> resultsMigrations();

}  // namespace earc::bench
