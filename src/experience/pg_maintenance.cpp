// earc-db inspect, verify and curate on a PostgreSQL store: the same
// reports as maintenance.cpp's on a file, from SQL the server answers.
// What only a file has (its bytes, a WAL, VACUUM, a copy) has no
// counterpart: sizes are the server's, and curate -o, --vacuum and
// --compact are refused.
#include <algorithm>
#include <sstream>

#include "earc/experience/maintenance.hpp"
#include "earc/experience/pg_schema.hpp"
#include "earc/experience/store.hpp"
#include "earc/experience/transfer.hpp"
#include "earc/util/format.hpp"

namespace earc::exp {

namespace {

// SQLite's GLOB pattern ('*', '?', [...]) as an anchored POSIX regular
// expression, for curate --drop-made-by.
std::string globToRegex(const std::string& glob) {
  std::string out = "^";
  bool in_class = false;
  for (char c : glob) {
    if (in_class) {
      out += c;
      if (c == ']') in_class = false;
    } else if (c == '*') {
      out += ".*";
    } else if (c == '?') {
      out += '.';
    } else if (c == '[') {
      out += c;
      in_class = true;
    } else {
      if (std::string_view("\\.^$|()+{}").find(c) != std::string_view::npos) out += '\\';
      out += c;
    }
  }
  return out + "$";
}

std::int64_t pgCount(PgConnection& db, const std::string& sql, const PgParams& params = {}) {
  return db.query(sql, params).int64At(0, 0);
}

std::string pgCurateDescription(const CurateSettings& s) {
  std::ostringstream out;
  auto add = [&](const std::string& part) { out << (out.tellp() > 0 ? " " : "") << part; };
  for (const std::string& m : s.merge) add("--merge " + maskedLocation(m));
  if (s.dedupe_eps >= 0) add("--dedupe " + formatNumber(s.dedupe_eps));
  if (s.drop_unused)
    add("--drop-unused" +
        (s.older_than_sessions > 0 ? " --older-than-sessions " + std::to_string(s.older_than_sessions) : ""));
  for (const std::string& b : s.drop_made_by) add("--drop-made-by \"" + b + "\"");
  return out.str();
}

}  // namespace

InspectReport pgInspectDatabase(const std::string& location, int sample_entries, int history_lines) {
  ExperienceStore store(location, wholeFileStoreOptions(true));
  PgConnection& db = store.pgConnection();
  InspectReport r;
  r.path = db.location();
  r.schema_version = store.schemaVersion();
  r.sessions = store.session();
  db.exec("BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY");  // one snapshot for every number
  r.file_bytes = pgCount(db,
                         "SELECT (pg_total_relation_size('earc.experiences') + pg_total_relation_size('earc.history') "
                         "+ pg_total_relation_size('earc.store_meta'))::bigint");
  PgResult classes = db.query(
      "SELECT kind, robot_count, signature, base_class, count(*), sum(octet_length(key))::bigint, "
      "sum(octet_length(paths))::bigint, sum(retrieved_count)::float8, sum(succeeded_count)::float8, "
      "avg(solve_time_s)::float8, avg(cost)::float8 FROM earc.experiences "
      "GROUP BY kind, robot_count, signature, base_class ORDER BY kind, robot_count, base_class, signature");
  for (int i = 0; i < classes.rows(); ++i) {
    ClassSummary c;
    c.cls = {kindFromName(classes.textAt(i, 0)).value_or(RobotKind::Mobile), static_cast<int>(classes.int64At(i, 1)),
             classes.textAt(i, 2), classes.textAt(i, 3)};
    c.entries = classes.int64At(i, 4);
    c.key_dim = c.entries ? classes.int64At(i, 5) / c.entries / 8 : 0;
    c.path_bytes = classes.int64At(i, 6);
    c.retrieved = static_cast<std::int64_t>(classes.doubleAt(i, 7));
    c.succeeded = static_cast<std::int64_t>(classes.doubleAt(i, 8));
    c.mean_solve_time_s = classes.doubleAt(i, 9);
    c.mean_cost = classes.doubleAt(i, 10);
    r.entries += c.entries;
    r.key_bytes += classes.int64At(i, 5);
    r.path_bytes += c.path_bytes;
    r.classes.push_back(std::move(c));
  }
  PgResult builds =
      db.query("SELECT made_by, count(*) AS n FROM earc.experiences GROUP BY made_by ORDER BY n DESC, made_by");
  for (int i = 0; i < builds.rows(); ++i) r.builds.emplace_back(builds.textAt(i, 0), builds.int64At(i, 1));
  PgResult sample = db.query(pgSelectExperiencesSql() + " ORDER BY id LIMIT $1",
                             PgParams().add(static_cast<std::int64_t>(sample_entries)));
  for (int i = 0; i < sample.rows(); ++i) {
    try {
      r.samples.push_back(readPgExperience(sample, i));
    } catch (const CorruptRowError&) {
      // inspect shows what it can; verify names the bad rows
    }
  }
  r.history = pgReadHistory(db, history_lines);
  db.exec("COMMIT");
  return r;
}

VerifyReport pgVerifyDatabase(const std::string& location) {
  VerifyReport r;
  std::unique_ptr<ExperienceStore> store;
  // A server that cannot be reached, a foreign or newer database: bad
  // input, one line. Past that point every problem is listed.
  withInputErrors(maskedLocation(location), [&] {
    store = std::make_unique<ExperienceStore>(location, wholeFileStoreOptions(true));
  });
  PgConnection& db = store->pgConnection();
  r.schema_version = store->schemaVersion();
  KeyDimensionCheck key_dims;
  try {
    pgForEachExperience(
        db, "ORDER BY id", {},
        [&](Experience&& e) {
          ++r.rows;
          if (auto problem = key_dims.add(e)) r.problems.push_back(*problem);
        },
        [&](const CorruptRowError& e) {
          ++r.rows;
          r.problems.push_back(e.what());
        });
    if (r.problems.empty()) {
      PgResult h = db.query(
          "SELECT (SELECT operation FROM earc.history ORDER BY id LIMIT 1), "
          "(SELECT coalesce(sum(rows_added - rows_removed), 0) FROM earc.history)::bigint");
      if (!h.isNull(0, 0) && h.textAt(0, 0) == "create" && h.int64At(0, 1) != r.rows)
        r.notes.push_back("the history counts " + std::to_string(h.int64At(0, 1)) +
                          " rows added and not removed, the database holds " + std::to_string(r.rows) +
                          ": rows were added or deleted outside earc");
    }
  } catch (const StoreError& e) {
    r.problems.push_back(e.what());
  }
  return r;
}

CurateReport pgCurateDatabase(const std::string& location, const CurateSettings& settings) {
  const std::string masked = maskedLocation(location);
  if (!settings.output.empty())
    throw InputError(masked, "-o", "a curated copy is for database files; export the store and import it instead");
  if (settings.vacuum || settings.compact)
    throw InputError(masked, settings.vacuum ? "--vacuum" : "--compact",
                     "for database files; PostgreSQL's autovacuum gives freed space back");
  for (const std::string& in : settings.merge)
    if (!isPostgresLocation(in)) requireDatabaseFile(in);
  CurateReport r;
  r.curated_path = masked;
  ExperienceStore store(location, wholeFileStoreOptions(false));
  store.describeHistory("curate", pgCurateDescription(settings));
  PgConnection& db = store.pgConnection();
  const std::string lock = "SELECT pg_advisory_xact_lock(" + std::to_string(kPgWriteLock) + ")";
  // A step's deletions, counted on the history line in its transaction.
  auto deleteWhere = [&](const std::string& where, const PgParams& params) {
    std::int64_t n = 0;
    db.write([&] {
      db.exec(lock);
      n = db.query("WITH d AS (DELETE FROM earc.experiences WHERE " + where + " RETURNING 1) SELECT count(*) FROM d",
                   params)
              .int64At(0, 0);
      pgRecordHistory(db, store.history(), 0, n);
    });
    return n;
  };
  r.rows_before = pgCount(db, "SELECT count(*) FROM earc.experiences");
  const std::string unused =
      "retrieved_count = 0 AND created_session <= (SELECT value FROM earc.store_meta WHERE name = 'sessions') - $1";
  const PgParams older = PgParams().add(static_cast<std::int64_t>(settings.older_than_sessions));
  if (settings.drop_unused && r.rows_before > 0 &&
      pgCount(db, "SELECT count(*) FROM earc.experiences WHERE retrieved_count > 0") == 0 &&
      pgCount(db, "SELECT count(*) FROM earc.experiences WHERE " + unused, older) == r.rows_before)
    throw InputError(masked, "--drop-unused",
                     "no entry has been retrieved yet (no learning plan has used this store): it would remove all " +
                         std::to_string(r.rows_before) + "; plan with the store first");
  if (settings.dedupe_eps >= 0) {
    std::vector<DedupeRow> rows;
    pgForEachExperience(db, "ORDER BY succeeded_count DESC, retrieved_count DESC, id ASC", {},
                        [&](Experience&& e) { rows.push_back({e.id, e.cls, std::move(e.key)}); });
    const std::vector<std::int64_t> drop = nearDuplicateIds(rows, settings.dedupe_eps);
    r.duplicates_removed = drop.empty() ? 0 : deleteWhere("id = ANY($1)", PgParams().addIds(drop));
  }
  if (settings.drop_unused) r.unused_removed = deleteWhere(unused, older);
  // As the file's curate: merged rows are checked against the rows kept.
  if (!settings.merge.empty()) {
    ImportSettings merge;
    merge.near_duplicate_eps = std::max(0.0, settings.dedupe_eps);
    merge.keep_sessions = false;
    r.merged = static_cast<std::int64_t>(importInto(store, settings.merge, merge).inserted);
  }
  for (const std::string& build : settings.drop_made_by) {
    const std::int64_t n = deleteWhere("made_by ~ $1", PgParams().add(globToRegex(build)));
    if (n == 0) r.made_by_unmatched.push_back(build);
    r.made_by_removed += n;
  }
  if (!r.made_by_unmatched.empty()) {
    PgResult builds = db.query(
        "SELECT made_by, count(*) AS n FROM earc.experiences GROUP BY made_by ORDER BY n DESC, made_by LIMIT 5");
    for (int i = 0; i < builds.rows(); ++i) r.builds_present.emplace_back(builds.textAt(i, 0), builds.int64At(i, 1));
  }
  db.write([&] { pgRecordHistory(db, store.history(), 0, 0, true); });
  r.rows_after = pgCount(db, "SELECT count(*) FROM earc.experiences");
  if (settings.dedupe_eps < 0)
    pgForEachExperience(db, "ORDER BY id", {}, [](Experience&&) {}, [&](const CorruptRowError&) { ++r.damaged_rows; });
  store.close();
  return r;
}

}  // namespace earc::exp
