// The benchmark's results: an SQLite file (application_id "EBNC",
// user_version 8, WAL) that trials are appended to as they finish, each in
// its own BEGIN IMMEDIATE transaction, so an interrupted run loses at most
// the trials that were running and resumes by skipping the finished ones.
//
// Schema (version 1):
//   trials(id, suite, robots, method, trial, seed, time_limit_s,
//          scenario_seed, planner_seed, success, planning_time_s,
//          wall_time_s, makespan, sum_of_costs, conflicts, db_hits,
//          peak_memory_kb, exit_status, term_signal, failure, finished_at)
//     UNIQUE (suite, robots, method, trial, seed, time_limit_s): the key a
//     resumed run skips on. Seeds are decimal TEXT (64-bit unsigned).
//     success is 1 only for a solution that `earc-plan validate` accepted
//     within the time limit; failure says why not (NULL on success).
//     planning_time_s is the planner's own figure (stats.planning_time_s),
//     NULL when the process died before reporting one.
//   Version 2 adds trials.jobs: how many trials the run had at once
//     (--jobs), NULL for trials recorded before it.
//   Version 3 adds trials.planner_version: the earc_version the trial's
//     solution reported (the build that planned it), NULL for trials
//     recorded before it and for planners that do not say.
//   Version 4 adds trials.bench_version: the earc-bench build that ran and
//     timed the trial (its --version), which need not be the planner's
//     (--plan-program); NULL for trials recorded before it.
//   Version 5 adds trials.planner_args: the arguments the run added to the
//     trial's `earc-plan plan` (--method-arg), as a JSON array of strings;
//     NULL for none, as for every trial recorded before it. All trials of
//     one method in a file have the same (see ResultsDb): the file is one
//     experiment per method, so that table, export and plot, which group
//     by method, never pool two settings in one cell.
//   Version 6 adds trials.scenario_file: the path of a scenario file's
//     trial (suite kFilesSuite) as earc-bench run was given it; NULL for
//     a suite's trials, and for every trial recorded before it.
//   Version 7 adds trials.lightning_problems,
//     lightning_problems_per_robot and lightning_problem_time_limit_s:
//     the run's options for growing the Lightning databases
//     (--lightning-problems, else --lightning-problems-per-robot; and
//     --lightning-problem-time-limit), on each lightning trial; NULL on
//     other methods' trials and on every trial recorded before it. A run
//     resumed with other ones is refused (runner.cpp), as is a lightning
//     trial added beside others with other ones, so that no cell pools
//     trials of differently grown databases.
//   Version 8 adds trials.learn, earc_db and earc_db_state: on each earc
//     and lightning trial whether its run let the databases learn
//     (--learn, 1 or 0), and on each earc trial the E-ARC database it used
//     (as the run was given it or made it) and where that database's
//     history stood when the run began (the token of its last line, NULL
//     for a database without one); NULL elsewhere and on every trial
//     recorded before it. A run resumed with another --learn for one of
//     its database methods is refused, as is a trial added beside others
//     of its method with another; so is a run whose E-ARC database is not
//     the one the file's earc trials of that kind of robot and --seed
//     used, as they found it (runner.cpp).
//   Version 9 adds trials.lower_bound (a crowd suite's trial: the sum of
//     its robots' own shortest paths in steps, bench/crowds.hpp) and
//     refine_first_time_s, refine_first_sum_of_costs,
//     refine_final_sum_of_costs, refine_final_makespan: the solution's
//     stats.refine (earc-plan --refine) when it has them; NULL otherwise
//     and on every trial recorded before it.
//   An older file is migrated when opened for writing, each version in one
//   BEGIN IMMEDIATE transaction with its version bump, and read as it is
//   otherwise.
//   databases(id, method, suite, robots, path, construction_time_s,
//             entries, size_bytes, problems, seed, recorded_at)
//     robots = 0 for a database that serves every robot count (E-ARC's).
//
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
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace earc::bench {

inline constexpr std::int64_t kResultsApplicationId = 0x45424E43;  // "EBNC"
inline constexpr int kResultsSchemaVersion = 9;
// A solution may report a planning time this much over its time limit
// (the planners poll their deadline) and still count as solved; later than
// that it is "solved after the time limit", a failure.
inline constexpr double kSolvedTimeLimitSlack = 1.01;
// The most robots a run or lightning-db plans for (lightning-db --robots).
inline constexpr int kMaxResultsRobots = 1024;

// How a run grows its Lightning databases (run --lightning-problems,
// --lightning-problems-per-robot, --lightning-problem-time-limit): one of
// the counts is set.
struct LightningSettings {
  std::optional<int> problems;            // this many, whatever the robot count
  std::optional<int> problems_per_robot;  // else this many per robot
  double problem_time_limit_s = 0;
  bool operator==(const LightningSettings&) const = default;
};

// The first option in which two settings differ, with each one's value as
// messages give it ("none (4 per robot)" for --lightning-problems unset;
// a limit as exactNumber writes it, "1.0000001").
struct LightningSettingDifference {
  std::string option, stored, given;
};
std::optional<LightningSettingDifference> lightningSettingDifference(const LightningSettings& stored,
                                                                     const LightningSettings& given);

struct TrialRecord {
  std::string suite;
  int robots = 0;
  std::string method;
  int trial = 0;
  std::uint64_t seed = 0;  // the run's --seed
  double time_limit_s = 0;
  std::uint64_t scenario_seed = 0;
  std::uint64_t planner_seed = 0;
  bool success = false;
  std::optional<double> planning_time_s;
  double wall_time_s = 0;
  std::optional<std::int64_t> makespan, sum_of_costs, conflicts, db_hits;
  std::optional<std::int64_t> peak_memory_kb;
  std::optional<int> exit_status;  // the planner process's exit code
  std::optional<int> term_signal;  // the signal that ended it
  std::string failure;             // empty on success
  std::string finished_at;         // ISO 8601 UTC
  std::optional<int> jobs;         // trials the run had at once; unknown before schema 2
  std::string planner_version;     // the solution's earc_version; "" unknown (before schema 3)
  std::string bench_version;       // the earc-bench that ran it; "" unknown (before schema 4)
  // Added to its `earc-plan plan` command (run --method-arg); empty: none
  // (and every trial before schema 5).
  std::vector<std::string> planner_args;
  // The scenario file of a kFilesSuite trial, as given to the run; ""
  // for a suite's trial (and every trial before schema 6).
  std::string scenario_file;
  // A lightning trial's: how its run grew the Lightning databases; unset
  // for other methods (and every trial before schema 7).
  std::optional<LightningSettings> lightning;
  // An earc or lightning trial's: whether its run let the databases learn
  // (--learn); unset for other methods (and every trial before schema 8).
  std::optional<bool> learn;
  // An earc trial's E-ARC database, as the run used it, and where that
  // database's history stood when the run began: the token of its last
  // line (experience/history.hpp), which names the file, wherever it is
  // moved or copied, as it was then. Unset for a database without a
  // history (experience schema before 5). "" and unset for other methods
  // (and every trial before schema 8).
  std::string earc_db;
  std::optional<std::int64_t> earc_db_state;
  // A crowd suite's trial: the lower bound its sum of costs is compared
  // with; unset elsewhere (and every trial before schema 9).
  std::optional<std::int64_t> lower_bound;
  // The solution's stats.refine, when the planner refined (--refine):
  // when the first plan was found, its sum of costs, and the final plan's.
  std::optional<double> refine_first_time_s;
  std::optional<std::int64_t> refine_first_sum_of_costs, refine_final_sum_of_costs, refine_final_makespan;
};

struct DatabaseRecord {
  std::string method;
  std::string suite;
  int robots = 0;  // 0: every robot count
  std::string path;
  std::optional<double> construction_time_s;
  std::optional<std::int64_t> entries;
  std::optional<std::int64_t> size_bytes;
  std::optional<std::int64_t> problems;
  std::optional<std::uint64_t> seed;
  std::string recorded_at;
};

// (suite, robots, method, trial) of the finished trials of one seed and
// time limit.
using TrialKey = std::tuple<std::string, int, std::string, int>;

class ResultsDb {
 public:
  // Opens or creates the file. Throws InputError naming the file, before
  // anything is read or written, when it is not a results database of this
  // program (not SQLite, another application_id, a newer schema version:
  // the message names both versions) or is damaged (a table of its schema
  // missing), as exp::checkFileIdentity checks the experience store, or
  // when a row holds a value no run writes (see above; two rows of one
  // method with different planner_args too): every row is read and
  // checked at open, as trials() and databases() read them.
  explicit ResultsDb(const std::string& path, bool read_only = false);
  ~ResultsDb();
  ResultsDb(const ResultsDb&) = delete;
  ResultsDb& operator=(const ResultsDb&) = delete;

  // Appends a trial in its own transaction; a trial already recorded under
  // the same key is left as it is (returns false). Not thread-safe: callers
  // serialize.
  bool addTrial(const TrialRecord& t);
  void addDatabase(const DatabaseRecord& d);

  std::set<TrialKey> finishedTrials(std::uint64_t seed, double time_limit_s) const;
  // Every trial, read (and checked) now.
  std::vector<TrialRecord> trials() const;
  // The trials as trials() last read them: at open, which reads every row
  // to check it, or again once addTrial has added one. One read serves a
  // resumed run's checks (runner.cpp) and the queries below, which answer
  // from it; what another process adds meanwhile is not in it.
  const std::vector<TrialRecord>& recordedTrials() const;
  // The planner arguments the file's trials of `method` ran with; nothing
  // when it has none of them.
  std::optional<std::vector<std::string>> plannerArgs(const std::string& method) const;
  // Whether the file's trials of `method` ran with --learn; nothing when
  // none of them recorded it (none yet, or all before schema 8).
  std::optional<bool> learn(const std::string& method) const;
  // The Lightning settings the file's lightning trials ran with; nothing
  // when none of them recorded any (none yet, or all before schema 7).
  std::optional<LightningSettings> lightningSettings() const;
  std::vector<DatabaseRecord> databases() const;
  bool hasDatabase(const std::string& method, const std::string& path) const;

  const std::string& path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// "--learn" or "no --learn (fixed databases)", for messages.
std::string learnText(bool learn);

// Now as "YYYY-MM-DDTHH:MM:SSZ".
std::string utcNow();

}  // namespace earc::bench
