#include "earc/bench/results_db.hpp"

#include <ctime>
#include <iterator>
#include <string_view>

#include "earc/bench/options.hpp"
#include "earc/experience/schema.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/io/input_error.hpp"
#include "earc/util/format.hpp"

namespace earc::bench {

namespace {

using exp::Connection;
using exp::OpenMode;
using exp::Statement;

constexpr std::string_view kSchemaV1 = R"sql(
CREATE TABLE trials (
  id INTEGER PRIMARY KEY,
  suite TEXT NOT NULL,
  robots INTEGER NOT NULL,
  method TEXT NOT NULL,
  trial INTEGER NOT NULL,
  seed TEXT NOT NULL,
  time_limit_s REAL NOT NULL,
  scenario_seed TEXT NOT NULL,
  planner_seed TEXT NOT NULL,
  success INTEGER NOT NULL CHECK (success IN (0, 1)),
  planning_time_s REAL,
  wall_time_s REAL NOT NULL,
  makespan INTEGER,
  sum_of_costs INTEGER,
  conflicts INTEGER,
  db_hits INTEGER,
  peak_memory_kb INTEGER,
  exit_status INTEGER,
  term_signal INTEGER,
  failure TEXT,
  finished_at TEXT NOT NULL,
  UNIQUE (suite, robots, method, trial, seed, time_limit_s)
);
CREATE TABLE databases (
  id INTEGER PRIMARY KEY,
  method TEXT NOT NULL,
  suite TEXT NOT NULL,
  robots INTEGER NOT NULL,
  path TEXT NOT NULL,
  construction_time_s REAL,
  entries INTEGER,
  size_bytes INTEGER,
  problems INTEGER,
  seed TEXT,
  recorded_at TEXT NOT NULL
);
)sql";

// The steps from version 1, kMigrations[v - 2] making version v:
// 2: how many trials ran at once. Side by side, trials disturb each
//    other's timings, and how depends on the order (see runner.cpp).
// 3: which build planned the trial, so that every figure can be traced to
//    its code.
// 4: which earc-bench ran and timed it: how trials are run changes their
//    timings too (see d3acb53 in the README), and --plan-program plans
//    with another build than the one timing.
constexpr std::string_view kMigrations[] = {
    "ALTER TABLE trials ADD COLUMN jobs INTEGER",
    "ALTER TABLE trials ADD COLUMN planner_version TEXT",
    "ALTER TABLE trials ADD COLUMN bench_version TEXT",
};
static_assert(std::size(kMigrations) + 1 == kResultsSchemaVersion, "a migration for every version after 1");

// What the file must be, checked as the experience store checks its own.
constexpr exp::TableSince kResultsTables[] = {{"trials", 1}, {"databases", 1}};
constexpr exp::FileIdentity kResultsIdentity{kResultsApplicationId, "earc-bench results database", "earc-bench",
                                              kResultsSchemaVersion, kResultsTables};

// Optional values are bound as '' and turned into NULL by NULLIF in SQL:
// the statement wrapper has no bind for NULL.
void bindOpt(Statement& s, int i, const std::optional<double>& v) {
  if (v) s.bind(i, *v); else s.bind(i, std::string_view(""));
}
void bindOpt(Statement& s, int i, const std::optional<std::int64_t>& v) {
  if (v) s.bind(i, *v); else s.bind(i, std::string_view(""));
}
void bindOpt(Statement& s, int i, const std::optional<int>& v) {
  if (v) s.bind(i, static_cast<std::int64_t>(*v)); else s.bind(i, std::string_view(""));
}

std::optional<double> doubleOpt(const Statement& s, int c) {
  if (s.columnType(c) == SQLITE_NULL) return std::nullopt;
  return s.doubleAt(c);
}
std::optional<std::int64_t> intOpt(const Statement& s, int c) {
  if (s.columnType(c) == SQLITE_NULL) return std::nullopt;
  return s.int64At(c);
}

std::uint64_t seedFrom(const std::string& text) { return text.empty() ? 0 : std::stoull(text); }

}  // namespace

// Every statement this program runs on a results database; each is
// prepared once at open, so a file without a column they name is refused
// before any work.
constexpr const char* kInsertTrial =
    "INSERT INTO trials (suite, robots, method, trial, seed, time_limit_s, scenario_seed, planner_seed, success,"
    " planning_time_s, wall_time_s, makespan, sum_of_costs, conflicts, db_hits, peak_memory_kb, exit_status,"
    " term_signal, failure, finished_at, jobs, planner_version, bench_version) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7,"
    " ?8, ?9, NULLIF(?10, ''), ?11, NULLIF(?12, ''), NULLIF(?13, ''), NULLIF(?14, ''), NULLIF(?15, ''),"
    " NULLIF(?16, ''), NULLIF(?17, ''), NULLIF(?18, ''), NULLIF(?19, ''), ?20, NULLIF(?21, ''), NULLIF(?22, ''),"
    " NULLIF(?23, '')) ON CONFLICT DO NOTHING";
constexpr const char* kInsertDatabase =
    "INSERT INTO databases (method, suite, robots, path, construction_time_s, entries, size_bytes, problems,"
    " seed, recorded_at) VALUES (?1, ?2, ?3, ?4, NULLIF(?5, ''), NULLIF(?6, ''), NULLIF(?7, ''),"
    " NULLIF(?8, ''), NULLIF(?9, ''), ?10)";
constexpr const char* kFinishedTrials =
    "SELECT suite, robots, method, trial FROM trials WHERE seed = ?1 AND time_limit_s = ?2";
#define EARC_TRIAL_COLUMNS_V1                                                                                  \
  "suite, robots, method, trial, seed, time_limit_s, scenario_seed, planner_seed, success, planning_time_s,"      \
  " wall_time_s, makespan, sum_of_costs, conflicts, db_hits, peak_memory_kb, exit_status, term_signal, failure," \
  " finished_at"
// kSelectTrials[v - 1] reads a version v file, older ones without
// migrating them (table, export, plot): NULL for the columns it lacks.
constexpr const char* kSelectTrials[] = {
    "SELECT " EARC_TRIAL_COLUMNS_V1 ", NULL, NULL, NULL FROM trials ORDER BY id",
    "SELECT " EARC_TRIAL_COLUMNS_V1 ", jobs, NULL, NULL FROM trials ORDER BY id",
    "SELECT " EARC_TRIAL_COLUMNS_V1 ", jobs, planner_version, NULL FROM trials ORDER BY id",
    "SELECT " EARC_TRIAL_COLUMNS_V1 ", jobs, planner_version, bench_version FROM trials ORDER BY id",
};
static_assert(std::size(kSelectTrials) == kResultsSchemaVersion, "a trial select for every version");
#undef EARC_TRIAL_COLUMNS_V1
constexpr const char* kSelectDatabases =
    "SELECT method, suite, robots, path, construction_time_s, entries, size_bytes, problems, seed, recorded_at"
    " FROM databases ORDER BY id";
constexpr const char* kHasDatabase =
    "SELECT 1 FROM databases WHERE method = ?1 AND path = ?2 LIMIT 1";
// Those a file of any version must run; the inserts only the current
// version can (older files are read-only: they were opened so).
constexpr const char* kReadStatements[] = {kFinishedTrials, kSelectDatabases, kHasDatabase};
constexpr const char* kWriteStatements[] = {kInsertTrial, kInsertDatabase};

struct ResultsDb::Impl {
  std::string path;
  Connection conn;
  int version = kResultsSchemaVersion;
  Impl(const std::string& p, bool read_only)
      : path(p), conn(p, read_only ? OpenMode::ReadOnly : OpenMode::ReadWrite, settings()) {}
  static exp::ConnectionSettings settings() {
    exp::ConnectionSettings s;
    s.own_application_id = kResultsApplicationId;
    return s;
  }
  // A file whose tables lack a column this program reads or writes (edited
  // or damaged) is bad input, named in one line like a missing table.
  Statement prepare(std::string_view sql) {
    try {
      return conn.prepare(sql);
    } catch (const exp::DamagedDatabaseError& e) {
      throw InputError(path, "", reasonAbout(e, path));
    }
  }
};

ResultsDb::ResultsDb(const std::string& path, bool read_only) {
  try {
    impl_ = std::make_unique<Impl>(path, read_only);
  } catch (const exp::StoreError& e) {
    throw InputError(path, "", "cannot open the results database: " + reasonAbout(e, path));
  }
  Connection& c = impl_->conn;
  int version = 0;
  try {
    version = exp::checkFileIdentity(c, kResultsIdentity);
  } catch (const exp::BusyError&) {
    throw;  // another process, not the file, is in the way
  } catch (const exp::StoreError& e) {
    // Foreign, not SQLite, newer, or without a table: the file given.
    throw InputError(path, "", reasonAbout(e, path));
  }
  if (version == 0) {
    if (read_only) throw exp::notYetADatabase(path, "an earc-bench results database");
    c.enableWal();
    c.write([&] {
      c.exec(kSchemaV1);
      for (std::string_view step : kMigrations) c.exec(step);
      c.exec("PRAGMA application_id = " + std::to_string(kResultsApplicationId));
      c.exec("PRAGMA user_version = " + std::to_string(kResultsSchemaVersion));
    });
    version = kResultsSchemaVersion;
  } else if (!read_only) {
    c.enableWal();
    for (int next = version + 1; next <= kResultsSchemaVersion; ++next) {
      // Another process may have migrated it meanwhile: decided again
      // under the write lock.
      c.write([&] {
        if (c.pragmaInt("user_version") < next) {
          c.exec(kMigrations[next - 2]);
          c.exec("PRAGMA user_version = " + std::to_string(next));
        }
      });
    }
    version = kResultsSchemaVersion;
  }
  impl_->version = version;
  // The inserts first: a missing column is named best by an INSERT ("table
  // trials has no column named X").
  if (version == kResultsSchemaVersion)
    for (const char* sql : kWriteStatements) impl_->prepare(sql);
  impl_->prepare(kSelectTrials[version - 1]);
  for (const char* sql : kReadStatements) impl_->prepare(sql);
}

ResultsDb::~ResultsDb() = default;

const std::string& ResultsDb::path() const { return impl_->path; }

bool ResultsDb::addTrial(const TrialRecord& t) {
  Connection& c = impl_->conn;
  return c.write([&] {
    Statement s = impl_->prepare(kInsertTrial);
    s.bind(1, t.suite).bind(2, t.robots).bind(3, t.method).bind(4, t.trial);
    s.bind(5, std::to_string(t.seed)).bind(6, t.time_limit_s);
    s.bind(7, std::to_string(t.scenario_seed)).bind(8, std::to_string(t.planner_seed));
    s.bind(9, t.success ? 1 : 0);
    bindOpt(s, 10, t.planning_time_s);
    s.bind(11, t.wall_time_s);
    bindOpt(s, 12, t.makespan);
    bindOpt(s, 13, t.sum_of_costs);
    bindOpt(s, 14, t.conflicts);
    bindOpt(s, 15, t.db_hits);
    bindOpt(s, 16, t.peak_memory_kb);
    bindOpt(s, 17, t.exit_status);
    bindOpt(s, 18, t.term_signal);
    s.bind(19, std::string_view(t.failure));
    s.bind(20, t.finished_at.empty() ? utcNow() : t.finished_at);
    bindOpt(s, 21, t.jobs);
    s.bind(22, std::string_view(t.planner_version));
    s.bind(23, std::string_view(t.bench_version));
    s.run();
    return sqlite3_changes(c.handle()) > 0;
  });
}

void ResultsDb::addDatabase(const DatabaseRecord& d) {
  Connection& c = impl_->conn;
  c.write([&] {
    Statement s = impl_->prepare(kInsertDatabase);
    s.bind(1, d.method).bind(2, d.suite).bind(3, d.robots).bind(4, d.path);
    bindOpt(s, 5, d.construction_time_s);
    bindOpt(s, 6, d.entries);
    bindOpt(s, 7, d.size_bytes);
    bindOpt(s, 8, d.problems);
    s.bind(9, d.seed ? std::to_string(*d.seed) : std::string());
    s.bind(10, d.recorded_at.empty() ? utcNow() : d.recorded_at);
    s.run();
  });
}

std::set<TrialKey> ResultsDb::finishedTrials(std::uint64_t seed, double time_limit_s) const {
  Statement s = impl_->prepare(kFinishedTrials);
  s.bind(1, std::to_string(seed)).bind(2, time_limit_s);
  std::set<TrialKey> keys;
  while (s.step())
    keys.emplace(s.textAt(0), static_cast<int>(s.int64At(1)), s.textAt(2), static_cast<int>(s.int64At(3)));
  return keys;
}

std::vector<TrialRecord> ResultsDb::trials() const {
  Statement s = impl_->prepare(kSelectTrials[impl_->version - 1]);
  std::vector<TrialRecord> out;
  while (s.step()) {
    TrialRecord t;
    t.suite = s.textAt(0);
    t.robots = static_cast<int>(s.int64At(1));
    t.method = s.textAt(2);
    t.trial = static_cast<int>(s.int64At(3));
    t.seed = seedFrom(s.textAt(4));
    t.time_limit_s = s.doubleAt(5);
    t.scenario_seed = seedFrom(s.textAt(6));
    t.planner_seed = seedFrom(s.textAt(7));
    t.success = s.int64At(8) != 0;
    t.planning_time_s = doubleOpt(s, 9);
    t.wall_time_s = s.doubleAt(10);
    t.makespan = intOpt(s, 11);
    t.sum_of_costs = intOpt(s, 12);
    t.conflicts = intOpt(s, 13);
    t.db_hits = intOpt(s, 14);
    t.peak_memory_kb = intOpt(s, 15);
    if (auto v = intOpt(s, 16)) t.exit_status = static_cast<int>(*v);
    if (auto v = intOpt(s, 17)) t.term_signal = static_cast<int>(*v);
    if (s.columnType(18) != SQLITE_NULL) t.failure = s.textAt(18);
    t.finished_at = s.textAt(19);
    if (auto v = intOpt(s, 20)) t.jobs = static_cast<int>(*v);
    if (s.columnType(21) != SQLITE_NULL) t.planner_version = s.textAt(21);
    if (s.columnType(22) != SQLITE_NULL) t.bench_version = s.textAt(22);
    out.push_back(std::move(t));
  }
  return out;
}

std::vector<DatabaseRecord> ResultsDb::databases() const {
  Statement s = impl_->prepare(kSelectDatabases);
  std::vector<DatabaseRecord> out;
  while (s.step()) {
    DatabaseRecord d;
    d.method = s.textAt(0);
    d.suite = s.textAt(1);
    d.robots = static_cast<int>(s.int64At(2));
    d.path = s.textAt(3);
    d.construction_time_s = doubleOpt(s, 4);
    d.entries = intOpt(s, 5);
    d.size_bytes = intOpt(s, 6);
    d.problems = intOpt(s, 7);
    if (s.columnType(8) != SQLITE_NULL) d.seed = seedFrom(s.textAt(8));
    d.recorded_at = s.textAt(9);
    out.push_back(std::move(d));
  }
  return out;
}

bool ResultsDb::hasDatabase(const std::string& method, const std::string& path) const {
  Statement s = impl_->prepare(kHasDatabase);
  s.bind(1, method).bind(2, path);
  return s.step();
}

std::string utcNow() { return utcTimeText(std::time(nullptr)); }

}  // namespace earc::bench
