// The benchmark's results: an SQLite file (application_id "EBNC", WAL) that
// trials are appended to as they finish, each in its own BEGIN IMMEDIATE
// transaction, so an interrupted run loses at most the trials that were
// running and resumes by skipping the finished ones. Its schema is
// migrations/results/*.sql: an older file is migrated when opened for
// writing, each version in one transaction with its version bump, and read
// as it is otherwise. Every row is checked as it is read (results_db.cpp).
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
  // An earc trial's E-ARC database as the run named it, and the token of
  // its history's last line when the run began (unset without a history);
  // "" and unset for other methods (and every trial before schema 8).
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
  // Opens or creates the file, reading and checking every row. Throws
  // InputError naming the file, before writing anything, when it is not a
  // results database of this program, is damaged or holds a bad row.
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
  // The trials as trials() last read them (at open, or after addTrial):
  // what another process added since is not in it. The queries below
  // answer from it.
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
