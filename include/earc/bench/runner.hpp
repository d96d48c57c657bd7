// `earc-bench run`: trials of every (suite, robot count, method) cell, each
// planned by its own child process under a wall-clock and a memory limit,
// validated by another (`earc-plan validate`), and appended to a results
// database as it finishes. A re-run with the same seed and time limit
// skips the trials already recorded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace earc::bench {

struct RunOptions {
  // Scenario files to run instead of the suites (suite kFilesSuite, one
  // trial per file); their databases are built from the files' robots.
  std::vector<std::string> scenario_files;
  std::vector<std::string> suites = {"mobile-obst", "arms"};
  std::vector<int> robots = {2, 4, 8};  // empty: every count of each suite
  std::vector<std::string> methods = {"earc", "arc", "lightning", "prioritized"};
  int trials = 2;
  double time_limit_s = 60.0;
  std::uint64_t seed = 1;
  std::string results = "bench-results.sqlite";
  std::string work_dir;                  // empty: <results>.work
  // E-ARC databases (earc-plan --db), built when missing; empty: one the run
  // builds, <work_dir>/earc-FAMILY[-pCOUNT]-sSEED[-learn].sqlite.
  std::string db_mobile, db_arms;
  // earc-db build --count for the databases the run builds itself (unset:
  // earc-db's default); refused beside db_mobile or db_arms, which are used
  // as they are (built with earc-db's default count when missing).
  std::optional<int> earc_db_count;
  std::string earc_db_program;           // empty: earc-db next to this program
  std::string lightning_dir;             // empty: <work_dir>/lightning
  // Lightning databases built when missing: problems = per_robot x robots
  // (the paper grows the database with the robot count), each planned for
  // at most problem_time_limit_s.
  int lightning_problems_per_robot = 4;
  std::optional<int> lightning_problems; // this many, whatever the count
  double lightning_problem_time_limit_s = 10.0;
  int jobs = 1;                          // trials at once (1: undisturbed timings)
  std::size_t memory_limit_mb = 4096;    // RLIMIT_AS of each child
  bool learn = false;                    // let database methods learn during trials
  bool keep_solutions = false;           // keep solved trials' solution files
  bool verbose = false;                  // one line per trial on stdout
  // Skip a method's trials at a robot count once it solved none of all
  // `trials` trials at a smaller count of the same suite (the paper stops
  // plotting such methods too). Cut trials are not recorded, only counted.
  bool cutoff = false;
  std::optional<double> wall_margin_s;   // unset: wallMargin(time_limit_s)
  std::string plan_program;              // empty: earc-plan next to this program
  // Arguments added to every `earc-plan plan` of a method (--method-arg
  // METHOD=ARG), recorded with each trial; one set per method in a file.
  std::map<std::string, std::vector<std::string>> method_args;
  std::string bench_program;             // empty: this program
};

// Seconds a trial's process may run beyond its time limit (start-up,
// loading, the planner's own validation) before it is killed.
double wallMargin(double time_limit_s);

// Validates SOLUTION with `validator` (an earc-plan) in a child, logs at
// LOG_STEM.validate.*: nothing when valid, else why in one line.
std::optional<std::string> validateSolution(const std::string& validator, const std::string& scenario,
                                            const std::string& solution, const std::string& log_stem,
                                            std::size_t memory_limit_mb);

struct ChildOutcome;

// A plan child's solution file, read once childFailure found nothing wrong:
// nothing, with `doc` filled, when it can be used; else why not in one line.
std::optional<std::string> readPlanSolution(const ChildOutcome& run, const std::string& solution,
                                            const std::string& err_path, nlohmann::json& doc);

// Whether a plan child refused its command rather than its scenario (exit 2
// with a failure that does not name the scenario file).
bool refusedItsCommand(const ChildOutcome& run, const std::string& failure, const std::string& scenario_file);

// The build that wrote a solution (its stats' earc_version), "" when it
// does not say.
std::string plannerVersion(const nlohmann::json& solution);

// "exit N" or the signal's name ("SIGSEGV"): how a child that was meant
// to exit 0 ended.
std::string exitDescription(const ChildOutcome& outcome);

struct RunSummary {
  std::size_t cells_total = 0;  // trials the options ask for
  std::size_t skipped = 0;      // already in the results database
  std::size_t run = 0;
  std::size_t solved = 0;
  std::size_t invalid = 0;      // solutions the validator rejected
  std::size_t cut = 0;          // not run: RunOptions::cutoff
  bool interrupted = false;
};

// Runs the trials `options` asks for that the results file lacks; progress to
// a terminal, per-trial lines and the run's table to `log`. Throws InputError
// on bad options before anything is run, or when a planner refuses its command.
RunSummary runBenchmark(const RunOptions& options, std::ostream& log);

}  // namespace earc::bench
