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
#include "earc/experience/schema.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/io/input_error.hpp"
#include "earc/util/format.hpp"

namespace earc::bench {

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

constexpr std::int64_t kNoCountLimit = std::numeric_limits<std::int64_t>::max();

// A value of a results row as a message shows it: 12, 1.5, inf, 'text'
// (cut short, on one line), NULL, a blob.
std::string resultValueText(const Statement& s, int c) {
  switch (s.columnType(c)) {
    case SQLITE_INTEGER: return std::to_string(s.int64At(c));
    case SQLITE_FLOAT: return formatNumber(s.doubleAt(c));
    case SQLITE_TEXT: return "'" + printableText(s.textAt(c), 40) + "'";
    case SQLITE_BLOB: return "a blob";
    default: return "NULL";
  }
}

// "2026-11-24T01:02:03Z", as utcNow() writes it.
bool isUtcTimeText(std::string_view t) {
  constexpr std::string_view kShape = "0000-00-00T00:00:00Z";
  if (t.size() != kShape.size()) return false;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (kShape[i] == '0' ? !isDigits(t.substr(i, 1)) : t[i] != kShape[i]) return false;
  return true;
}

// Every row is read back through one check of every column against what
// addTrial and addDatabase write (a run, lightning-db): a value no run
// writes, by a hand edit or another program, refuses the file like a
// missing column does, in one line naming the file, the table, the row's
// id and the column:
//   r.sqlite: trials row id 3, column robots: -3 is not a robot count from 2 to 1024
// What a run writes: suite and method names earc-bench has (bench/suites.hpp,
// resultSuiteNames: the suites and kFilesSuite;
// databases: method earc or lightning, robots 0 or a count); robot counts
// 2 to kMaxResultsRobots; trial numbers, counts (makespan, sum_of_costs,
// conflicts, db_hits, peak_memory_kb, entries, size_bytes, problems) and
// times (seconds, finite) of 0 or more; a positive time limit; success 0
// or 1, with a failure exactly when 0 and a planning time of at most
// kSolvedTimeLimitSlack times the limit when 1; exit status 0 to 255;
// signals 1 to 127; jobs 1 or more; seeds as decimal TEXT of a 64-bit
// unsigned number, as std::to_string writes it (no sign, no leading zero);
// times of day as utcNow() writes them; failure, versions and path as TEXT
// (path not empty); scenario_file NULL or a path (not empty) of a trial
// of kFilesSuite; planner_args NULL or a JSON array of at least one
// string that plannerArgsProblem (bench/options.hpp) accepts, the same
// (or NULL) in every row of a method:
//   r.sqlite: trials row id 7, column planner_args: '["--db-k=5"]' beside
//   no planner arguments for method earc in row id 1: ...
// and the Lightning settings NULL, or on a lightning trial a positive time
// and one positive count (lightning_problems or
// lightning_problems_per_robot), the same in every lightning trial that
// has them; learn NULL, or 0 or 1 on an earc or lightning trial, the same
// in every trial of a method that has it; earc_db NULL or a path (not
// empty) on an earc trial, and earc_db_state NULL or an integer beside one.
//
// One row of a results table as read back: each value checked, as it is
// read, against what addTrial and addDatabase write (above). A
// value no run writes throws InputError naming the file, the table, the
// row's id (column 0 of every select) and the column (SQLite's name of
// it). Columns an older schema lacks are selected as NULL and read as
// optional, so they never fail.
class CheckedResultRow {
 public:
  CheckedResultRow(const Statement& s, const std::string& path, std::string_view table)
      : s_(s), path_(path), table_(table), id_(s.int64At(0)) {}

  [[noreturn]] void bad(int c, const std::string& reason) const {
    throw InputError(path_, std::string(table_) + " row id " + std::to_string(id_) + ", column " +
                                s_.columnName(c),
                     reason);
  }
  bool isNull(int c) const { return s_.columnType(c) == SQLITE_NULL; }
  std::string value(int c) const { return resultValueText(s_, c); }

  // An INTEGER from lo to most; `what` is what it must be ("a robot count
  // from 2 to 128").
  std::int64_t integer(int c, std::int64_t lo, std::int64_t most, std::string_view what) const {
    // The type first: after a conversion (int64At of a TEXT value) SQLite
    // no longer says what the value was.
    if (s_.columnType(c) != SQLITE_INTEGER || s_.int64At(c) < lo || s_.int64At(c) > most)
      bad(c, value(c) + " is not " + std::string(what));
    return s_.int64At(c);
  }
  std::optional<std::int64_t> optInteger(int c, std::int64_t lo, std::int64_t most, std::string_view what) const {
    if (isNull(c)) return std::nullopt;
    return integer(c, lo, most, what);
  }
  std::optional<std::int64_t> optCount(int c) const { return optInteger(c, 0, kNoCountLimit, "a count (0 or more)"); }
  // Seconds: a finite REAL (or a whole number SQLite stored as INTEGER),
  // 0 or more, above 0 where `positive`.
  double seconds(int c, bool positive = false) const {
    const int type = s_.columnType(c);
    const bool number = type == SQLITE_FLOAT || type == SQLITE_INTEGER;
    if (!number || !std::isfinite(s_.doubleAt(c)) || s_.doubleAt(c) < 0 || (positive && s_.doubleAt(c) == 0))
      bad(c, value(c) + " is not a number of seconds" + (positive ? " above 0" : " (0 or more)"));
    return s_.doubleAt(c);
  }
  std::optional<double> optSeconds(int c) const {
    if (isNull(c)) return std::nullopt;
    return seconds(c);
  }
  std::string text(int c) const {
    if (s_.columnType(c) != SQLITE_TEXT) bad(c, value(c) + " is not text");
    return s_.textAt(c);
  }
  // TEXT or NULL; NULL reads as "".
  std::string optText(int c) const { return isNull(c) ? std::string() : text(c); }
  // One of `names`, which the message lists.
  std::string oneOf(int c, const std::vector<std::string>& names, const char* what) const {
    const std::string v = text(c);
    if (std::find(names.begin(), names.end(), v) == names.end()) {
      std::string list;
      for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
      bad(c, value(c) + " is not " + what + " (" + list + ")");
    }
    return v;
  }
  // A seed as addTrial writes it: std::to_string of a 64-bit unsigned number.
  std::uint64_t seed(int c) const {
    std::uint64_t v = 0;
    const std::string t = s_.columnType(c) == SQLITE_TEXT ? s_.textAt(c) : std::string();
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || ec != std::errc() || end != t.data() + t.size() || std::to_string(v) != t)
      bad(c, value(c) + " is not a seed (a whole number from 0 to 2^64-1 as decimal text)");
    return v;
  }
  // NULL (none), or a JSON array of the arguments, as addTrial writes
  // them: at least one, each a string plannerArgsProblem accepts.
  std::vector<std::string> plannerArgs(int c) const {
    if (isNull(c)) return {};
    const std::string t = text(c);
    std::vector<std::string> args;
    const nlohmann::json j = nlohmann::json::parse(t, nullptr, /*allow_exceptions=*/false);
    const bool strings = j.is_array() && !j.empty() &&
                         std::all_of(j.begin(), j.end(), [](const nlohmann::json& a) { return a.is_string(); });
    if (!strings) bad(c, value(c) + " is not a JSON array of planner arguments (strings)");
    for (const auto& a : j) args.push_back(a.get<std::string>());
    if (const auto why = plannerArgsProblem(args)) bad(c, value(c) + " is not what a run gives a planner: " + *why);
    return args;
  }
  std::string utcTime(int c) const {
    if (s_.columnType(c) != SQLITE_TEXT || !isUtcTimeText(s_.textAt(c)))
      bad(c, value(c) + " is not a UTC time like 2026-11-24T01:02:03Z");
    return s_.textAt(c);
  }

 private:
  const Statement& s_;
  const std::string& path_;
  std::string_view table_;
  std::int64_t id_;
};

// What a trial's robot count must be, in messages.
const std::string& robotCountText() {
  static const std::string text = "a robot count from 2 to " + std::to_string(kMaxResultsRobots);
  return text;
}

// The trial column of a Lightning option.
int lightningColumn(const std::string& option) {
  return option == "--lightning-problems" ? 26 : option == "--lightning-problems-per-robot" ? 27 : 28;
}

// Columns 26 to 28 of a trial row (readTrialRow): NULL, or on a lightning
// trial a positive time and exactly one of the two counts, positive.
constexpr int kLightningColumns[] = {26, 27, 28};
std::optional<LightningSettings> readLightningSettings(const CheckedResultRow& r, const std::string& method) {
  const auto set = std::find_if_not(std::begin(kLightningColumns), std::end(kLightningColumns),
                                    [&r](int c) { return r.isNull(c); });
  if (set == std::end(kLightningColumns)) return std::nullopt;
  if (method != "lightning")
    r.bad(*set, r.value(*set) + " beside method " + method + ": only a lightning trial records Lightning settings");
  constexpr std::int64_t most = std::numeric_limits<int>::max();
  LightningSettings l;
  if (auto v = r.optInteger(26, 1, most, "a number of problems (1 or more)")) l.problems = static_cast<int>(*v);
  if (auto v = r.optInteger(27, 1, most, "a number of problems per robot (1 or more)"))
    l.problems_per_robot = static_cast<int>(*v);
  if (l.problems && l.problems_per_robot)
    r.bad(27, r.value(27) + " beside lightning_problems " + r.value(26) +
                  ": problems per robot are for a run without a number of problems");
  if (!l.problems && !l.problems_per_robot)
    r.bad(26, "NULL beside lightning_problems_per_robot NULL: a lightning trial records one of them");
  l.problem_time_limit_s = r.seconds(28, true);
  return l;
}

TrialRecord readTrialRow(const CheckedResultRow& r) {
  static const std::vector<std::string> suites = resultSuiteNames();
  TrialRecord t;
  t.suite = r.oneOf(1, suites, "a suite earc-bench runs");
  t.robots = static_cast<int>(r.integer(2, 2, kMaxResultsRobots, robotCountText()));
  t.method = r.oneOf(3, allMethods(), "a method earc-bench runs");
  t.trial = static_cast<int>(r.integer(4, 0, std::numeric_limits<int>::max(), "a trial number (0 or more)"));
  t.seed = r.seed(5);
  t.time_limit_s = r.seconds(6, true);
  t.scenario_seed = r.seed(7);
  t.planner_seed = r.seed(8);
  t.success = r.integer(9, 0, 1, "0 or 1") == 1;
  t.planning_time_s = r.optSeconds(10);
  t.wall_time_s = r.seconds(11);
  t.makespan = r.optCount(12);
  t.sum_of_costs = r.optCount(13);
  t.conflicts = r.optCount(14);
  t.db_hits = r.optCount(15);
  t.peak_memory_kb = r.optCount(16);
  if (auto v = r.optInteger(17, 0, 255, "an exit status from 0 to 255")) t.exit_status = static_cast<int>(*v);
  if (auto v = r.optInteger(18, 1, 127, "a signal number from 1 to 127")) t.term_signal = static_cast<int>(*v);
  t.failure = r.optText(19);
  // A solved trial has no failure, a failed one says why (runner.cpp).
  if (t.success && !r.isNull(19)) r.bad(19, r.value(19) + " beside success 1: a solved trial has no failure");
  if (!t.success && t.failure.empty()) r.bad(19, r.value(19) + " beside success 0: a failed trial says why it failed");
  if (t.success && t.planning_time_s && *t.planning_time_s > t.time_limit_s * kSolvedTimeLimitSlack)
    r.bad(10, formatNumber(*t.planning_time_s) + " s of a solved trial is beyond its time limit of " +
                  formatNumber(t.time_limit_s) + " s");
  t.finished_at = r.utcTime(20);
  if (auto v = r.optInteger(21, 1, std::numeric_limits<int>::max(), "a number of jobs (1 or more)"))
    t.jobs = static_cast<int>(*v);
  t.planner_version = r.optText(22);
  t.bench_version = r.optText(23);
  t.planner_args = r.plannerArgs(24);
  t.scenario_file = r.optText(25);
  // A scenario file's trial names its file (or did not, before schema 6);
  // a suite's has none.
  if (!r.isNull(25) && t.suite != kFilesSuite)
    r.bad(25, r.value(25) + " beside suite " + t.suite + ": only a scenario file's trial (suite " + kFilesSuite +
                  ") names a file");
  if (!r.isNull(25) && t.scenario_file.empty()) r.bad(25, "'' is not a path");
  t.lightning = readLightningSettings(r, t.method);
  // Whether the databases learned: a database method's trial says (or did
  // not, before schema 8); another method's has none to learn.
  if (!r.isNull(29) && !usesDatabase(t.method))
    r.bad(29, r.value(29) + " beside method " + t.method +
                  ": only a trial of a method with a database (earc, lightning) records --learn");
  if (auto v = r.optInteger(29, 0, 1, "0 or 1")) t.learn = *v == 1;
  // An earc trial's E-ARC database, and where its history stood.
  if (!r.isNull(30) && t.method != "earc")
    r.bad(30, r.value(30) + " beside method " + t.method + ": only an earc trial records an E-ARC database");
  t.earc_db = r.optText(30);
  if (!r.isNull(30) && t.earc_db.empty()) r.bad(30, "'' is not a path");
  if (!r.isNull(31) && r.isNull(30))
    r.bad(31, r.value(31) + " beside earc_db NULL: only a trial that records its E-ARC database records its state");
  t.earc_db_state = r.optInteger(31, std::numeric_limits<std::int64_t>::min(),
                                 std::numeric_limits<std::int64_t>::max(), "a history token (a whole number)");
  t.lower_bound = r.optCount(32);
  t.refine_first_time_s = r.optSeconds(33);
  t.refine_first_sum_of_costs = r.optCount(34);
  t.refine_final_sum_of_costs = r.optCount(35);
  t.refine_final_makespan = r.optCount(36);
  return t;
}

DatabaseRecord readDatabaseRow(const CheckedResultRow& r) {
  static const std::vector<std::string> suites = resultSuiteNames();
  static const std::vector<std::string> methods = {"earc", "lightning"};
  DatabaseRecord d;
  d.method = r.oneOf(1, methods, "a method with a database");
  d.suite = r.oneOf(2, suites, "a suite earc-bench runs");
  static const std::string robots = "0 (every robot count) or " + robotCountText();
  d.robots = static_cast<int>(r.integer(3, 0, kMaxResultsRobots, robots));
  if (d.robots == 1) r.bad(3, "1 is not " + robots);
  d.path = r.text(4);
  if (d.path.empty()) r.bad(4, "'' is not a path");
  d.construction_time_s = r.optSeconds(5);
  d.entries = r.optCount(6);
  d.size_bytes = r.optCount(7);
  d.problems = r.optCount(8);
  if (!r.isNull(9)) d.seed = r.seed(9);
  d.recorded_at = r.utcTime(10);
  return d;
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
