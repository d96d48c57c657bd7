#include "earc/bench/results_db.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <ctime>
#include <iterator>
#include <limits>
#include <map>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>

#include "earc/bench/options.hpp"
#include "earc/bench/results_migrations.hpp"
#include "earc/bench/suites.hpp"
#include "results_rows.hpp"
#include "earc/experience/schema.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/io/input_error.hpp"
#include "earc/util/format.hpp"

namespace earc::bench {

using results_detail::CheckedResultRow;
using results_detail::lightningColumn;
using results_detail::readDatabaseRow;
using results_detail::readTrialRow;

namespace {

using exp::Connection;
using exp::OpenMode;
using exp::Statement;

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

}  // namespace


// Every statement this program runs on a results database; each is
// prepared once at open, so a file without a column they name is refused
// before any work.
constexpr const char* kInsertTrial =
    "INSERT INTO trials (suite, robots, method, trial, seed, time_limit_s, scenario_seed, planner_seed, success,"
    " planning_time_s, wall_time_s, makespan, sum_of_costs, conflicts, db_hits, peak_memory_kb, exit_status,"
    " term_signal, failure, finished_at, jobs, planner_version, bench_version, planner_args, scenario_file,"
    " lightning_problems, lightning_problems_per_robot, lightning_problem_time_limit_s, learn, earc_db,"
    " earc_db_state, lower_bound, refine_first_time_s, refine_first_sum_of_costs, refine_final_sum_of_costs,"
    " refine_final_makespan)"
    " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, NULLIF(?10, ''), ?11, NULLIF(?12, ''), NULLIF(?13, ''),"
    " NULLIF(?14, ''), NULLIF(?15, ''), NULLIF(?16, ''), NULLIF(?17, ''), NULLIF(?18, ''), NULLIF(?19, ''), ?20,"
    " NULLIF(?21, ''), NULLIF(?22, ''), NULLIF(?23, ''), NULLIF(?24, ''), NULLIF(?25, ''), NULLIF(?26, ''),"
    " NULLIF(?27, ''), NULLIF(?28, ''), NULLIF(?29, ''), NULLIF(?30, ''), NULLIF(?31, ''), NULLIF(?32, ''),"
    " NULLIF(?33, ''), NULLIF(?34, ''), NULLIF(?35, ''), NULLIF(?36, '')) ON CONFLICT DO NOTHING";
// A trial of the method run with other planner arguments (NULLIF as the
// insert writes them): the trial would make the file mix two settings.
constexpr const char* kOtherPlannerArgs =
    "SELECT id, planner_args FROM trials WHERE method = ?1 AND planner_args IS NOT NULLIF(?2, '') LIMIT 1";
// A trial of the method whose run set --learn otherwise: the trial would
// make the file mix databases that learned with fixed ones.
constexpr const char* kOtherLearn =
    "SELECT id, learn FROM trials WHERE method = ?1 AND learn IS NOT NULL AND learn != ?2 LIMIT 1";
// The first lightning trial that recorded its Lightning settings: every
// other that did has the same (a file is checked so when opened).
constexpr const char* kFirstLightningSettings =
    "SELECT id, lightning_problems, lightning_problems_per_robot, lightning_problem_time_limit_s FROM trials"
    " WHERE method = 'lightning' AND lightning_problem_time_limit_s IS NOT NULL ORDER BY id LIMIT 1";
constexpr const char* kInsertDatabase =
    "INSERT INTO databases (method, suite, robots, path, construction_time_s, entries, size_bytes, problems,"
    " seed, recorded_at) VALUES (?1, ?2, ?3, ?4, NULLIF(?5, ''), NULLIF(?6, ''), NULLIF(?7, ''),"
    " NULLIF(?8, ''), NULLIF(?9, ''), ?10)";
constexpr const char* kFinishedTrials =
    "SELECT suite, robots, method, trial FROM trials WHERE seed = ?1 AND time_limit_s = ?2";
constexpr const char* kTrialColumnsV1 =
    "id, suite, robots, method, trial, seed, time_limit_s, scenario_seed, planner_seed, success, planning_time_s,"
    " wall_time_s, makespan, sum_of_costs, conflicts, db_hits, peak_memory_kb, exit_status, term_signal, failure,"
    " finished_at";
namespace {
// The trial columns each later version added (resultsMigrations()), in the order
// readTrialRow reads them after version 1's.
struct AddedColumn {
  const char* name;
  int since;
};
constexpr AddedColumn kAddedTrialColumns[] = {
    {"jobs", 2},
    {"planner_version", 3},
    {"bench_version", 4},
    {"planner_args", 5},
    {"scenario_file", 6},
    {"lightning_problems", 7},
    {"lightning_problems_per_robot", 7},
    {"lightning_problem_time_limit_s", 7},
    {"learn", 8},
    {"earc_db", 8},
    {"earc_db_state", 8},
    {"lower_bound", 9},
    {"refine_first_time_s", 9},
    {"refine_first_sum_of_costs", 9},
    {"refine_final_sum_of_costs", 9},
    {"refine_final_makespan", 9},
};
static_assert(kAddedTrialColumns[std::size(kAddedTrialColumns) - 1].since == kResultsSchemaVersion,
              "the columns of every version");
// Reads a version `version` file, an older one without migrating it
// (table, export, plot): NULL for the columns it lacks. The row's id
// first, for CheckedResultRow.
std::string selectTrials(int version) {
  std::string sql = std::string("SELECT ") + kTrialColumnsV1;
  for (const AddedColumn& c : kAddedTrialColumns) sql += std::string(", ") + (c.since <= version ? c.name : "NULL");
  return sql + " FROM trials ORDER BY id";
}
}  // namespace
constexpr const char* kSelectDatabases =
    "SELECT id, method, suite, robots, path, construction_time_s, entries, size_bytes, problems, seed, recorded_at"
    " FROM databases ORDER BY id";
constexpr const char* kHasDatabase =
    "SELECT 1 FROM databases WHERE method = ?1 AND path = ?2 LIMIT 1";
// Those a file of any version must run; the inserts only the current
// version can (older files are read-only: they were opened so).
constexpr const char* kReadStatements[] = {kFinishedTrials, kSelectDatabases, kHasDatabase};
constexpr const char* kWriteStatements[] = {kInsertTrial, kInsertDatabase, kOtherPlannerArgs, kOtherLearn,
                                            kFirstLightningSettings};

struct ResultsDb::Impl {
  std::string path;
  Connection conn;
  int version = kResultsSchemaVersion;
  // The trials as trials() last read them (at open, to check every row),
  // until addTrial adds one: recordedTrials() and the queries on them.
  std::optional<std::vector<TrialRecord>> trials_read;
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

// Refused, as exp::checkFileIdentity refuses an experience store: not
// SQLite, another application_id, a newer schema version (the message
// names both), a table of the schema missing; and a row holding a value no
// run writes (two rows of one method with different planner_args too).
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
      for (const ResultsMigration& m : resultsMigrations()) c.exec(m.sql);
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
          c.exec(resultsMigrations()[static_cast<std::size_t>(next - 1)].sql);
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
  impl_->prepare(selectTrials(version));
  for (const char* sql : kReadStatements) impl_->prepare(sql);
  // Every row checked before any work, whatever the command then reads.
  trials();
  databases();
}

ResultsDb::~ResultsDb() = default;

const std::string& ResultsDb::path() const { return impl_->path; }

bool ResultsDb::addTrial(const TrialRecord& t) {
  Connection& c = impl_->conn;
  const std::string args = t.planner_args.empty() ? std::string() : nlohmann::json(t.planner_args).dump();
  return c.write([&] {
    // Under the write lock: another run into the same file may have added
    // the method's first trials since this one checked (runner.cpp).
    Statement other = impl_->prepare(kOtherPlannerArgs);
    other.bind(1, t.method).bind(2, std::string_view(args));
    if (other.step())
      throw InputError(impl_->path, "", "its " + t.method + " trials ran with " +
                                            (other.columnType(1) == SQLITE_NULL ? "no planner arguments"
                                                                                : other.textAt(1)) +
                                            " (row id " + std::to_string(other.int64At(0)) + "); a trial run with " +
                                            (args.empty() ? "none" : args) +
                                            " is not added: a results file holds one set per method");
    if (t.learn) {
      Statement other_learn = impl_->prepare(kOtherLearn);
      other_learn.bind(1, t.method).bind(2, *t.learn ? 1 : 0);
      if (other_learn.step())
        throw InputError(impl_->path, "", "its " + t.method + " trials ran with " + learnText(!*t.learn) +
                                              " (row id " + std::to_string(other_learn.int64At(0)) +
                                              "); a trial run with " + learnText(*t.learn) +
                                              " is not added: a results file holds one --learn setting per method");
    }
    if (t.lightning) {
      Statement first = impl_->prepare(kFirstLightningSettings);
      if (first.step()) {
        LightningSettings stored;
        if (first.columnType(1) != SQLITE_NULL) stored.problems = static_cast<int>(first.int64At(1));
        if (first.columnType(2) != SQLITE_NULL) stored.problems_per_robot = static_cast<int>(first.int64At(2));
        stored.problem_time_limit_s = first.doubleAt(3);
        if (const auto d = lightningSettingDifference(stored, *t.lightning))
          throw InputError(impl_->path, "", "its lightning trials ran with " + d->option + " " + d->stored +
                                                " (row id " + std::to_string(first.int64At(0)) +
                                                "); a trial run with " + d->given +
                                                " is not added: a results file holds one Lightning setting");
      }
    }
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
    s.bind(24, std::string_view(args));
    s.bind(25, std::string_view(t.scenario_file));
    const std::optional<LightningSettings>& l = t.lightning;
    bindOpt(s, 26, l ? l->problems : std::nullopt);
    bindOpt(s, 27, l ? l->problems_per_robot : std::nullopt);
    bindOpt(s, 28, l ? std::optional<double>(l->problem_time_limit_s) : std::nullopt);
    bindOpt(s, 29, t.learn ? std::optional<int>(*t.learn ? 1 : 0) : std::nullopt);
    s.bind(30, std::string_view(t.earc_db));
    bindOpt(s, 31, t.earc_db_state);
    bindOpt(s, 32, t.lower_bound);
    bindOpt(s, 33, t.refine_first_time_s);
    bindOpt(s, 34, t.refine_first_sum_of_costs);
    bindOpt(s, 35, t.refine_final_sum_of_costs);
    bindOpt(s, 36, t.refine_final_makespan);
    s.run();
    const bool added = sqlite3_changes(c.handle()) > 0;
    if (added) impl_->trials_read.reset();
    return added;
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
  Statement s = impl_->prepare(selectTrials(impl_->version));
  std::vector<TrialRecord> out;
  // Per method, its first row (index in out, id): every other row of it
  // ran with the same arguments.
  std::map<std::string, std::pair<std::size_t, std::int64_t>> first_of_method;
  // The first lightning trial with Lightning settings (its settings, id).
  std::optional<std::pair<LightningSettings, std::int64_t>> first_lightning;
  // Per method, the --learn of its first trial that records one (and its id).
  std::map<std::string, std::pair<bool, std::int64_t>> first_learn;
  while (s.step()) {
    const CheckedResultRow row(s, impl_->path, "trials");
    out.push_back(readTrialRow(row));
    const TrialRecord& t = out.back();
    if (t.lightning && !first_lightning) first_lightning.emplace(*t.lightning, s.int64At(0));
    if (t.lightning) {
      if (const auto d = lightningSettingDifference(first_lightning->first, *t.lightning))
        row.bad(lightningColumn(d->option), row.value(lightningColumn(d->option)) + " beside " + d->stored +
                                                " in row id " + std::to_string(first_lightning->second) +
                                                ": a results file holds one Lightning setting");
    }
    if (t.learn) {
      const auto [first, inserted] = first_learn.emplace(t.method, std::pair{*t.learn, s.int64At(0)});
      if (!inserted && first->second.first != *t.learn)
        row.bad(29, row.value(29) + " beside " + (first->second.first ? "1" : "0") + " of method " + t.method +
                        " in row id " + std::to_string(first->second.second) +
                        ": a results file holds one --learn setting per method");
    }
    const auto [first, inserted] = first_of_method.emplace(t.method, std::pair{out.size() - 1, s.int64At(0)});
    const std::vector<std::string>& before = out[first->second.first].planner_args;
    if (inserted || before == t.planner_args) continue;
    row.bad(24, row.value(24) + " beside " + (before.empty() ? "NULL" : "'" + nlohmann::json(before).dump() + "'") +
                    " of method " + t.method + " in row id " + std::to_string(first->second.second) +
                    ": a results file holds one set of planner arguments per method");
  }
  impl_->trials_read = out;
  return out;
}

// One read serves a resumed run's checks (runner.cpp) and the queries.
const std::vector<TrialRecord>& ResultsDb::recordedTrials() const {
  if (!impl_->trials_read) trials();
  return *impl_->trials_read;
}

std::vector<DatabaseRecord> ResultsDb::databases() const {
  Statement s = impl_->prepare(kSelectDatabases);
  std::vector<DatabaseRecord> out;
  while (s.step()) out.push_back(readDatabaseRow(CheckedResultRow(s, impl_->path, "databases")));
  return out;
}

std::optional<LightningSettings> ResultsDb::lightningSettings() const {
  // Every row was checked as it was read: the first that has them tells
  // for all.
  for (const TrialRecord& t : recordedTrials())
    if (t.lightning) return t.lightning;
  return std::nullopt;
}

std::optional<bool> ResultsDb::learn(const std::string& method) const {
  // Every row was checked as it was read: the first that has it tells for
  // all.
  for (const TrialRecord& t : recordedTrials())
    if (t.method == method && t.learn) return t.learn;
  return std::nullopt;
}

std::optional<std::vector<std::string>> ResultsDb::plannerArgs(const std::string& method) const {
  // Every row was checked as it was read: the method's first tells for
  // all.
  for (const TrialRecord& t : recordedTrials())
    if (t.method == method) return t.planner_args;
  return std::nullopt;
}

bool ResultsDb::hasDatabase(const std::string& method, const std::string& path) const {
  Statement s = impl_->prepare(kHasDatabase);
  s.bind(1, method).bind(2, path);
  return s.step();
}

std::optional<LightningSettingDifference> lightningSettingDifference(const LightningSettings& stored,
                                                                     const LightningSettings& given) {
  // --lightning-problems, when either has it, decides the count alone.
  const auto count = [](const LightningSettings& l) {
    return l.problems ? std::to_string(*l.problems)
                      : "none (" + std::to_string(l.problems_per_robot.value_or(0)) + " per robot)";
  };
  if (stored.problems != given.problems) return {{"--lightning-problems", count(stored), count(given)}};
  if (!stored.problems && stored.problems_per_robot != given.problems_per_robot)
    return {{"--lightning-problems-per-robot", std::to_string(stored.problems_per_robot.value_or(0)),
             std::to_string(given.problems_per_robot.value_or(0))}};
  // Each as a run gives it, and so always told apart: 1.0000001, not
  // %.17g's 1.0000001000000001.
  if (stored.problem_time_limit_s != given.problem_time_limit_s)
    return {{"--lightning-problem-time-limit", exactNumber(stored.problem_time_limit_s),
             exactNumber(given.problem_time_limit_s)}};
  return std::nullopt;
}

std::string learnText(bool learn) { return learn ? "--learn" : "no --learn (fixed databases)"; }

std::string utcNow() { return utcTimeText(std::time(nullptr)); }

}  // namespace earc::bench
