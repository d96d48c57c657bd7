// The PostgreSQL migrations in migrations/postgresql/*.sql, embedded in
// the binary from the files themselves at build time
// (tools/embed_migrations.cmake), and the schema's identity check and
// migration. To add a migration: write migrations/postgresql/NNNN_name.sql.
#include <ctime>
#include <iterator>

#include "earc/experience/pg_schema.hpp"
#include "earc/util/version.hpp"

namespace earc::exp {

namespace {

constexpr Migration kPgMigrations[] = {
#include "migrations/postgresql.inc"
};

}  // namespace

std::span<const Migration> pgMigrations() { return kPgMigrations; }

int pgCurrentSchemaVersion() { return static_cast<int>(std::size(kPgMigrations)); }

int pgCheckIdentity(PgConnection& db) {
  PgResult r = db.query(
      "SELECT to_regclass('earc.store_meta') IS NOT NULL, "
      "(SELECT count(*) FROM pg_catalog.pg_class c JOIN pg_catalog.pg_namespace n ON n.oid = c.relnamespace "
      " WHERE c.relkind IN ('r', 'p', 'v', 'm') AND n.nspname NOT IN ('pg_catalog', 'information_schema') "
      " AND n.nspname NOT LIKE 'pg_toast%' AND n.nspname NOT LIKE 'pg_temp%')::bigint");
  const bool ours = r.textAt(0, 0) == std::string(1, '\1');
  if (!ours) {
    if (r.int64At(0, 1) > 0)
      throw ForeignDatabaseError(db.location() + ": not an earc experience database (it holds " +
                                 std::to_string(r.int64At(0, 1)) +
                                 " tables but no earc schema); give an empty database or one earc made");
    return 0;
  }
  PgResult meta = db.query(
      "SELECT (SELECT value FROM earc.store_meta WHERE name = 'application_id'), "
      "(SELECT value FROM earc.store_meta WHERE name = 'schema_version')");
  if (meta.isNull(0, 0) || meta.int64At(0, 0) != kApplicationId || meta.isNull(0, 1))
    throw ForeignDatabaseError(db.location() +
                               ": not an earc experience database (its schema \"earc\" is another application's)");
  const std::int64_t version = meta.int64At(0, 1);
  if (version > pgCurrentSchemaVersion())
    throw SchemaVersionError(db.location() + ": schema version " + std::to_string(version) +
                                 " is newer than this program's " + std::to_string(pgCurrentSchemaVersion()) +
                                 "; use a newer earc",
                             static_cast<int>(version), pgCurrentSchemaVersion());
  return static_cast<int>(version);
}

int pgMigrate(PgConnection& db, int target) {
  if (target < 0) target = pgCurrentSchemaVersion();
  int from = -1;
  for (;;) {
    // Each step re-reads the version under the write lock, in its own
    // transaction: two processes migrating at once apply each step once.
    int reached = -1;
    db.write([&] {
      reached = -1;
      db.exec("SELECT pg_advisory_xact_lock(" + std::to_string(kPgWriteLock) + ")");
      int version = pgCheckIdentity(db);
      if (version >= target) {
        reached = version;
        return;
      }
      if (from < 0) from = version;
      const Migration& m = kPgMigrations[version];
      db.exec(m.sql);
      db.query("UPDATE earc.store_meta SET value = $1 WHERE name = 'schema_version'", PgParams().add(m.version));
      version = m.version;
      if (version == target && version >= 2) {
        const bool creating = from == 0;
        const std::string to = "schema " + std::to_string(target);
        pgRecordHistory(db,
                        HistoryWriter(creating ? "create" : "migrate",
                                      creating ? to : "schema " + std::to_string(from) + " to " + to.substr(7)),
                        0, 0, true);
      }
    });
    if (reached >= 0) return reached;
  }
}

void pgRecordHistory(PgConnection& db, const HistoryWriter& writer, std::int64_t added, std::int64_t removed,
                     bool even_if_unchanged) {
  if (added == 0 && removed == 0 && !even_if_unchanged) return;
  db.query(
      "INSERT INTO earc.history (token, at, program, operation, detail, rows_added, rows_removed) "
      "VALUES ($1, $2, $3, $4, $5, $6, $7) ON CONFLICT (token) DO UPDATE SET "
      "rows_added = earc.history.rows_added + EXCLUDED.rows_added, "
      "rows_removed = earc.history.rows_removed + EXCLUDED.rows_removed",
      PgParams()
          .add(writer.token())
          .add(static_cast<std::int64_t>(std::time(nullptr)))
          .add(version())
          .add(writer.operation())
          .add(writer.detail())
          .add(added)
          .add(removed));
}

std::int64_t pgHistoryRowsAdded(PgConnection& db, const HistoryWriter& writer) {
  PgResult r = db.query("SELECT rows_added FROM earc.history WHERE token = $1", PgParams().add(writer.token()));
  return r.rows() ? r.int64At(0, 0) : 0;
}

HistoryTail pgReadHistory(PgConnection& db, int limit) {
  HistoryTail tail;
  PgResult total = db.query("SELECT count(*) FROM earc.history");
  tail.total = total.int64At(0, 0);
  PgResult last = db.query(
      "SELECT id, at, program, operation, detail, rows_added, rows_removed, token FROM "
      "(SELECT * FROM earc.history ORDER BY id DESC LIMIT $1) h ORDER BY id",
      PgParams().add(static_cast<std::int64_t>(limit)));
  for (int i = 0; i < last.rows(); ++i)
    tail.lines.push_back({last.int64At(i, 0), last.int64At(i, 1), last.textAt(i, 2), last.textAt(i, 3),
                          last.textAt(i, 4), last.int64At(i, 5), last.int64At(i, 6), last.int64At(i, 7)});
  return tail;
}

}  // namespace earc::exp
