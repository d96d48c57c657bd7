// The rows of a results database read back: every column checked against
// what addTrial and addDatabase write.
#include "results_rows.hpp"


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
#include "earc/bench/suites.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/io/input_error.hpp"
#include "earc/util/format.hpp"

namespace earc::bench::results_detail {

std::string resultValueText(const Statement& s, int c) {
  switch (s.columnType(c)) {
    case SQLITE_INTEGER: return std::to_string(s.int64At(c));
    case SQLITE_FLOAT: return formatNumber(s.doubleAt(c));
    case SQLITE_TEXT: return "'" + printableText(s.textAt(c), 40) + "'";
    case SQLITE_BLOB: return "a blob";
    default: return "NULL";
  }
}

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


// What a trial's robot count must be, in messages.
const std::string& robotCountText() {
  static const std::string text = "a robot count from 2 to " + std::to_string(kMaxResultsRobots);
  return text;
}

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


}  // namespace earc::bench::results_detail
