// The benchmark runner's parts, shared by runner.cpp (the run),
// runner_consistency.cpp (a run held to its results file),
// runner_databases.cpp (the databases it builds) and runner_trial.cpp (one
// trial). Internal to src/bench.
#pragma once

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <thread>
#include <tuple>
#include <string_view>
#include <utility>

#include "earc/bench/child.hpp"
#include "earc/bench/runner.hpp"
#include "earc/bench/crowds.hpp"
#include "earc/bench/options.hpp"
#include "earc/bench/report.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/bench/suites.hpp"
#include "earc/cli/stop_signals.hpp"
#include "earc/methods/builder.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/experience/store.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/methods/database_solver.hpp"
#include "earc/scene/solution.hpp"
#include "earc/util/format.hpp"
#include "earc/util/hash.hpp"
#include "earc/util/progress.hpp"
#include "earc/util/version.hpp"

namespace earc::bench::runner {

namespace fs = std::filesystem;

// Wall-clock limit of one `earc-plan validate` (a 32-robot solution with a
// long makespan takes seconds; a hang must not stop the run).
inline constexpr double kValidateWallLimitS = 300.0;
// Wall-clock limit of `earc-db build` (its default problem counts take
// minutes; a build that runs for hours has hung).
inline constexpr double kEarcDbWallLimitS = 4 * 3600.0;

struct Cell {
  const Suite* suite;  // null for a scenario file's trial
  int robots;
  int trial;
  std::string method;
  const ScenarioFile* file = nullptr;

  std::string suiteName() const { return file ? kFilesSuite : suite->name; }
  const std::string& family() const { return file ? file->family : suite->family; }
  // "mobile-obst-32-t4", "files-8-t0": names the trial's files and logs.
  std::string trialName() const { return suiteName() + "-" + std::to_string(robots) + "-t" + std::to_string(trial); }
};

inline std::string fmtSeconds(double s) { return formatNumber("%.3g", s); }

// What the run reads of an E-ARC database that is there: its entries, and
// its history, oldest line first (none before experience schema 5).
struct EarcDbFacts {
  std::int64_t entries = 0;
  std::vector<exp::HistoryLine> history;
};

// The E-ARC databases that existed before the run, by family:
// validateOptions opens each once to check it, and what it read is
// recorded and held to.
using ExistingEarcDbs = std::map<std::string, EarcDbFacts>;

ChildFault faultFor(const std::string& method);

std::int64_t fileSize(const std::string& path);

// Scenarios, logs and built databases: the one given, or RESULTS.work.
std::string workDir(const RunOptions& o);

// 16 hex digits, for names.
std::string hex16(std::uint64_t v);

// What an E-ARC database built from a file covers: its robots' geometry,
// and for arms their layout too (the relative base transforms make the
// classes). Files with the same key need one build between them.
std::string earcBuildKey(const ScenarioFile& f);

// Why `earc-db build --scenario` would refuse a file's robots (its arms
// have no pair of one class), or "".
std::string unbuildableReason(const ScenarioFile& f);

// The files of a family its E-ARC database is built from: the first of
// each build key, in the order given, leaving out unbuildable arm layouts.
std::vector<const ScenarioFile*> earcBuildFiles(const std::vector<ScenarioFile>& files, const std::string& family);

// The E-ARC database of a family: the one given, or one the run builds in
// its work directory, named by everything its rows come of.
std::string earcDbPath(const RunOptions& o, const std::vector<ScenarioFile>& files, const std::string& family);

// An existing E-ARC database's facts, opened read-only. Throws InputError
// when it cannot be read.
EarcDbFacts earcDbFacts(const RunOptions& o, const std::vector<ScenarioFile>& files, const std::string& family);

// Where a database's history stands (its last line's token), as earc
// trials record it; nothing without a history.
std::optional<std::int64_t> earcDbState(const EarcDbFacts& f);

// The families of robots (mobile, arms) a run plans for: its scenario
// files', else its suites'.
std::set<std::string> runFamilies(const RunOptions& o, const std::vector<ScenarioFile>& files);

// Every option checked before anything is created, run or recorded; the
// facts of the E-ARC databases that exist. Throws InputError.
ExistingEarcDbs validateOptions(const RunOptions& o, const std::vector<ScenarioFile>& files);

class Runner {
 public:
  Runner(const RunOptions& o, const std::vector<ScenarioFile>& files, ExistingEarcDbs existing, std::ostream& log);

  RunSummary run();

 private:
  const std::vector<std::string>& argsOf(const std::string& method) const;

  // " with ARGS" / " with no planner arguments", for messages.
  static std::string withArgs(const std::vector<std::string>& args);

  void requireSamePlannerArgs() const;

  // How this run grows the Lightning databases, as its lightning trials
  // record it.
  LightningSettings lightningSettings() const;

  void requireSameLightningSettings() const;

  bool runs(const std::string& method) const;

  // The same for --learn, per method with a database: trials whose
  // database learned as they went are another experiment than those of a
  // fixed one. Files from before schema 8 have none to hold the run to.
  void requireSameLearn() const;

  // The families of robots (mobile, arms) whose E-ARC databases this
  // run's earc trials use.
  std::set<std::string> families() const { return runFamilies(o_, files_); }

  // The family of a recorded trial: its suite's, or its scenario file's
  // when that is one of this run's files; nothing for another file.
  std::optional<std::string> familyOf(const TrialRecord& t) const;

  void requireSameEarcDb() const;

  void requireSameEarcDbCount() const;

  void requireSameFiles() const;

  static std::string ordinal(int n);

  RunSummary finishInterrupted();

  std::vector<Cell> pending();

  std::size_t methodIndex(const std::string& m) const;

  // The problems a Lightning database for this many robots is grown from.
  int lightningProblems(int robots) const;

  std::string lightningDb(const Cell& c) const;

  // earcDbPath's, worked out once per family.
  const std::string& earcDb(const std::string& family) const { return earc_dbs_.at(family); }

  // One line for a database whose build (a child, logs at STEM.out and
  // .err) failed; the method's trials then fail with its planner's own
  // message about the file.
  static void buildFailed(const std::string& path, const ChildOutcome& out, const std::string& stem,
                          std::string_view method);

  void ensureLightningDb(const Cell& c);

  // Databases are built (in a child, timed) when missing and recorded in
  // the results with their construction time; a database that was given
  // is recorded without one.
  void prepareDatabases(const std::vector<Cell>& cells);

  void warnNoClassFits(const std::string& family, const std::string& path);

  std::optional<double> buildEarcDb(const std::string& family, const std::string& path);

  TrialSeeds seedsOf(const Cell& c) const;

  // The trial's scenario in WORK/scenarios, written once: a suite's
  // generated, a file's copied as it was read.
  std::string scenarioFile(const Cell& c);
  std::string scenarioFile(const ScenarioFile& f) { return scenarioFile(Cell{nullptr, f.robots(), f.trial, "", &f}); }

  std::vector<std::string> planArgv(const Cell& c, const std::string& scenario, const std::string& solution,
                                    std::uint64_t seed) const;

  // The trial's figures from a solution readPlanSolution accepted; its
  // solved flag.
  static bool readStats(const nlohmann::json& doc, TrialRecord& t);

  TrialRecord runTrial(const Cell& c);

  void validate(const Cell& c, const std::string& scenario, const std::string& solution, const std::string& stem,
                TrialRecord& t);

  bool cutOff(const Cell& c);

  // c's trial is recorded (or abandoned): wake workers waiting in cutOff.
  void done(const Cell& c);

  void record(const TrialRecord& t);

  void printTable();

  const RunOptions& o_;
  const std::vector<ScenarioFile>& files_;
  std::ostream& log_;
  ResultsDb db_;
  const ExistingEarcDbs existing_;
  // Each family's E-ARC database (earcDbPath), and where it stood when the
  // run began, for its earc trials to record: those there before, and
  // those built here.
  std::map<std::string, std::string> earc_dbs_;
  std::map<std::string, std::optional<std::int64_t>> earc_states_;
  std::string work_, lightning_dir_, plan_, bench_;
  RunSummary summary_;
  std::mutex record_mutex_, scenario_mutex_, lightning_mutex_;
  // (suite, method, robots) -> (trials recorded, solved), for cutOff.
  std::map<std::tuple<std::string, std::string, int>, std::pair<int, int>> outcomes_;
  bool outcomes_loaded_ = false;
  std::vector<std::string> cut_notes_;
  std::map<std::tuple<std::string, std::string, int>, int> running_;  // trials in flight (cutoff only)
  std::condition_variable finished_cv_;
};

}  // namespace earc::bench::runner
