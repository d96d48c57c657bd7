#include "earc/bench/runner.hpp"

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
#include <utility>

#include "earc/bench/child.hpp"
#include "earc/bench/crowds.hpp"
#include "earc/bench/options.hpp"
#include "earc/bench/report.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/bench/suites.hpp"
#include "earc/experience/builder.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/experience/store.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/planning/database_solver.hpp"
#include "earc/scene/solution.hpp"
#include "earc/util/format.hpp"
#include "earc/util/hash.hpp"
#include "earc/util/progress.hpp"
#include "earc/util/version.hpp"

namespace fs = std::filesystem;

namespace earc::bench {

namespace {

// Wall-clock limit of one `earc-plan validate` (a 32-robot solution with a
// long makespan takes seconds; a hang must not stop the run).
constexpr double kValidateWallLimitS = 300.0;
// Wall-clock limit of `earc-db build` (its default problem counts take
// minutes; a build that runs for hours has hung).
constexpr double kEarcDbWallLimitS = 4 * 3600.0;

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

// EARC_BENCH_FAULT=METHOD:crash|hang (test only): the plan child of that
// method commits the fault instead of planning.
ChildFault faultFor(const std::string& method) {
  const char* env = std::getenv("EARC_BENCH_FAULT");
  if (!env) return ChildFault::None;
  const std::string spec = env;
  const auto colon = spec.find(':');
  if (colon == std::string::npos || spec.substr(0, colon) != method) return ChildFault::None;
  const std::string what = spec.substr(colon + 1);
  if (what == "crash") return ChildFault::Crash;
  if (what == "hang") return ChildFault::Hang;
  return ChildFault::None;
}

std::string fmtSeconds(double s) { return formatNumber("%.3g", s); }

std::int64_t fileSize(const std::string& path) {
  std::error_code ec;
  auto n = fs::file_size(path, ec);
  return ec ? -1 : static_cast<std::int64_t>(n);
}

// Scenarios, logs and built databases: the one given, or RESULTS.work.
std::string workDir(const RunOptions& o) { return o.work_dir.empty() ? o.results + ".work" : o.work_dir; }

// 16 hex digits, for names.
std::string hex16(std::uint64_t v) {
  char hex[20];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(v));
  return hex;
}

// What an E-ARC database built from a file covers: its robots' geometry,
// and for arms their layout too (the relative base transforms make the
// classes). Files with the same key need one build between them.
std::string earcBuildKey(const ScenarioFile& f) {
  nlohmann::json robots = scenarioWorldJson(f.scenario)["robots"];
  for (auto& r : robots) r.erase("name");
  if (f.family == "arms") return robots.dump();
  std::set<std::string> shapes;
  for (const auto& r : robots) shapes.insert(r.dump());
  std::string key;
  for (const std::string& one : shapes) key += one;
  return key;
}

// Why `earc-db build --scenario` would refuse a file's robots (its arms
// have no pair of one class), or "".
std::string unbuildableReason(const ScenarioFile& f) {
  std::vector<RobotSpec> arms;
  for (const RobotSpec& r : f.scenario.robots)
    if (r.kind == RobotKind::Manipulator) arms.push_back(r);
  if (arms.size() < 2 || !exp::armPairClasses(arms, f.scenario.resolution).empty()) return "";
  return exp::noArmPairClassReason(arms);
}

// The files of a family that its E-ARC database is built from, one
// `earc-db build --scenario` each: the first of each build key, in the
// order given. An arm layout with no pair the database can hold has
// nothing to build, and its E-ARC trials plan as ARC (the run warns why).
std::vector<const ScenarioFile*> earcBuildFiles(const std::vector<ScenarioFile>& files, const std::string& family) {
  std::vector<const ScenarioFile*> out;
  std::set<std::string> keys;
  for (const ScenarioFile& f : files)
    if (f.family == family && keys.insert(earcBuildKey(f)).second && unbuildableReason(f).empty())
      out.push_back(&f);
  return out;
}

// The E-ARC database of a family: the one given, or one the run builds in
// its work directory, named by what its rows come of, as a Lightning
// database is: WORK/earc-FAMILY[-pCOUNT]-sSEED[-learn].sqlite, COUNT as
// --earc-db-count gives it (none: earc-db's default), SEED the run's, and
// -learn when trials add to it; for scenario files
// WORK/earc-files-FAMILY-ROBOTS-..., ROBOTS a hash of the robot geometries
// (and arm layouts) it is built for. So a run takes a database only where
// it would have built the same one: another --seed, count or --learn, a
// run into another results file sharing the work directory, files of
// other robots, each build their own.
std::string earcDbPath(const RunOptions& o, const std::vector<ScenarioFile>& files, const std::string& family) {
  const std::string& given = family == "arms" ? o.db_arms : o.db_mobile;
  if (!given.empty()) return given;
  std::string name = (files.empty() ? "earc-" : "earc-files-") + family;
  if (!files.empty()) {
    // Of the builds' keys, not the files: in any order, and whichever
    // file of a key stands for it, the builds are the same.
    std::set<std::string> keys;
    for (const ScenarioFile* f : earcBuildFiles(files, family)) keys.insert(earcBuildKey(*f));
    std::string all;
    for (const std::string& key : keys) all += key + "\n";
    name += "-" + hex16(fnv1a64(all));
  }
  if (o.earc_db_count) name += "-p" + std::to_string(*o.earc_db_count);
  name += "-s" + std::to_string(o.seed);
  if (o.learn) name += "-learn";
  return workDir(o) + "/" + name + ".sqlite";
}

// What the run reads of an E-ARC database that is there: its entries, and
// its history, oldest line first (none before experience schema 5).
struct EarcDbFacts {
  std::int64_t entries = 0;
  std::vector<exp::HistoryLine> history;
};

// An existing E-ARC database, opened read-only as the trials' `earc-plan
// --no-learn` opens it. One that cannot be read (a foreign file, a newer
// schema version) is bad input: every earc trial would fail on it, and be
// recorded, and be skipped when resumed.
EarcDbFacts earcDbFacts(const RunOptions& o, const std::vector<ScenarioFile>& files, const std::string& family) {
  const std::string path = earcDbPath(o, files, family);
  const bool given = !(family == "arms" ? o.db_arms : o.db_mobile).empty();
  const std::string option = given ? "--db-" + family : "";
  if (fs::is_directory(path)) throw InputError(path, option, "a directory, not an E-ARC database");
  try {
    exp::StoreOptions so;
    so.read_only = true;
    so.new_session = false;
    exp::ExperienceStore store(path, so);
    EarcDbFacts f;
    f.entries = static_cast<std::int64_t>(store.size());
    f.history = store.readHistoryLines(std::numeric_limits<int>::max()).lines;  // either engine
    return f;
  } catch (const std::exception& e) {
    throw InputError(path, option, "not a usable E-ARC database: " + reasonAbout(e, path) +
                                       (given ? "" : " (remove it to have it built again)"));
  }
}

// Where a database's history stands (its last line's token), as earc
// trials record it; nothing without a history.
std::optional<std::int64_t> earcDbState(const EarcDbFacts& f) {
  if (f.history.empty()) return std::nullopt;
  return f.history.back().token;
}

// The E-ARC databases that existed before the run, by family:
// validateOptions opens each once to check it, and what it read is
// recorded and held to.
using ExistingEarcDbs = std::map<std::string, EarcDbFacts>;

// The families of robots (mobile, arms) a run plans for: its scenario
// files', else its suites'.
std::set<std::string> runFamilies(const RunOptions& o, const std::vector<ScenarioFile>& files) {
  std::set<std::string> out;
  for (const ScenarioFile& f : files) out.insert(f.family);
  for (const std::string& name : files.empty() ? o.suites : std::vector<std::string>{})
    out.insert(suiteByName(name).family);
  return out;
}

class Runner {
 public:
  Runner(const RunOptions& o, const std::vector<ScenarioFile>& files, ExistingEarcDbs existing, std::ostream& log)
      : o_(o), files_(files), log_(log), db_(o.results), existing_(std::move(existing)) {
    work_ = workDir(o);
    lightning_dir_ = o.lightning_dir.empty() ? work_ + "/lightning" : o.lightning_dir;
    const std::string here = executableDir();
    plan_ = o.plan_program.empty() ? here + "/earc-plan" : o.plan_program;
    bench_ = o.bench_program.empty() ? here + "/earc-bench" : o.bench_program;
    requireSamePlannerArgs();
    requireSameLightningSettings();
    requireSameLearn();
    requireSameFiles();
    for (const std::string& family : families()) earc_dbs_[family] = earcDbPath(o_, files_, family);
    requireSameEarcDbCount();
    requireSameEarcDb();
    for (const auto& [family, facts] : existing_) earc_states_[family] = earcDbState(facts);
    for (const char* sub : {"scenarios", "solutions", "logs"}) fs::create_directories(work_ + "/" + sub);
  }

  RunSummary run() {
    const auto cells = pending();
    if (cells.empty()) {
      log_ << "nothing to run: all " << summary_.cells_total << " trials are in " << o_.results << "\n";
      printTable();
      return summary_;
    }
    log_ << "earc-bench run: " << cells.size() << (cells.size() == 1 ? " trial" : " trials") << " to run (" << summary_.skipped
         << " already recorded), time limit " << fmtSeconds(o_.time_limit_s) << " s, " << o_.jobs
         << (o_.jobs == 1 ? " job" : " jobs") << ", results " << o_.results << "\n";
    prepareDatabases(cells);
    if (interruptFlag().load()) return finishInterrupted();
    Progress progress("bench", cells.size());
    std::atomic<std::size_t> next{0};
    auto work = [&] {
      for (;;) {
        if (interruptFlag().load()) return;
        const std::size_t i = next.fetch_add(1);
        if (i >= cells.size()) return;
        const Cell& c = cells[i];
        if (o_.cutoff && cutOff(c)) {
          progress.tick();
          continue;
        }
        if (interruptFlag().load()) {
          if (o_.cutoff) done(c);
          return;
        }
        if (c.method == "lightning") ensureLightningDb(c);
        progress.setStatus(c.suiteName() + " " + std::to_string(c.robots) + " " + c.method + " #" +
                           std::to_string(c.trial));
        TrialRecord t = runTrial(c);
        if (interruptFlag().load() && !t.success && t.failure.rfind("interrupted", 0) == 0) {
          if (o_.cutoff) done(c);
          return;
        }
        record(t);
        if (o_.cutoff) done(c);
        progress.tick();
      }
    };
    // The first error of any worker (a trial refused for its
    // --method-arg, a results file that cannot be written) stops the
    // others as an interrupt does: running trials are killed and not
    // recorded. It is thrown once they have all stopped.
    std::exception_ptr error;
    std::mutex error_mutex;
    auto worker = [&] {
      try {
        work();
      } catch (...) {
        {
          std::lock_guard lock(error_mutex);
          if (!error) error = std::current_exception();
        }
        {
          // Set under the mutex cutOff's waiters check it under: set
          // between their check and their wait, they would sleep for good.
          std::lock_guard lock(record_mutex_);
          interruptFlag().store(true);
        }
        finished_cv_.notify_all();
      }
    };
    std::vector<std::thread> threads;
    for (int j = 1; j < std::max(1, o_.jobs); ++j) threads.emplace_back(worker);
    worker();
    for (auto& t : threads) t.join();
    progress.finish();
    if (error) {
      interruptFlag().store(false);  // the error stopped the run, not a signal
      std::rethrow_exception(error);
    }
    if (interruptFlag().load()) return finishInterrupted();
    log_ << "ran " << summary_.run << " trials: " << summary_.solved << " solved";
    if (summary_.invalid) log_ << ", " << summary_.invalid << " INVALID solutions";
    log_ << "\n";
    for (const auto& line : cut_notes_) log_ << line << "\n";
    printTable();
    return summary_;
  }

 private:
  const std::vector<std::string>& argsOf(const std::string& method) const {
    static const std::vector<std::string> none;
    const auto it = o_.method_args.find(method);
    return it == o_.method_args.end() ? none : it->second;
  }

  // " with ARGS" / " with no planner arguments", for messages.
  static std::string withArgs(const std::vector<std::string>& args) {
    return args.empty() ? " with no planner arguments" : " with " + plannerArgsText(args);
  }

  // A results file holds one experiment per method: table, export and
  // plot group trials by method, so trials of one method run with other
  // planner arguments would be pooled into one cell, and a resumed run
  // would skip trials that ran with the old ones. Refused before
  // anything runs; to measure one setting against another, a results
  // file each, or earc-bench compare.
  void requireSamePlannerArgs() const {
    for (const std::string& m : o_.methods) {
      const auto recorded = db_.plannerArgs(m);
      if (!recorded || *recorded == argsOf(m)) continue;
      throw InputError(o_.results, "--method-arg",
                       "its " + m + " trials ran" + withArgs(*recorded) + "; this run gives " + m + " " +
                           (argsOf(m).empty() ? "none" : plannerArgsText(argsOf(m))) +
                           ": a results file holds one set of planner arguments per method (give another "
                           "--results, or measure one against the other with earc-bench compare)");
    }
  }

  // How this run grows the Lightning databases, as its lightning trials
  // record it.
  LightningSettings lightningSettings() const {
    LightningSettings l;
    l.problems = o_.lightning_problems;
    if (!l.problems) l.problems_per_robot = o_.lightning_problems_per_robot;
    l.problem_time_limit_s = o_.lightning_problem_time_limit_s;
    return l;
  }

  // The same for Lightning's databases: its trials grown from other
  // problems, or under another limit per problem, are another experiment,
  // and a resumed run would put them in the cells of the first. Files
  // from before schema 7 (or without a lightning trial) have no settings
  // to hold the run to.
  void requireSameLightningSettings() const {
    if (!runs("lightning")) return;
    const auto recorded = db_.lightningSettings();
    if (!recorded) return;
    if (const auto d = lightningSettingDifference(*recorded, lightningSettings()))
      throw InputError(o_.results, d->option,
                       "its lightning trials ran with " + d->stored + "; this run gives " + d->given +
                           ": a results file holds one Lightning database setting (give the same, or another "
                           "--results)");
  }

  bool runs(const std::string& method) const {
    return std::find(o_.methods.begin(), o_.methods.end(), method) != o_.methods.end();
  }

  // The same for --learn, per method with a database: trials whose
  // database learned as they went are another experiment than those of a
  // fixed one. Files from before schema 8 have none to hold the run to.
  void requireSameLearn() const {
    for (const std::string& m : o_.methods) {
      const auto recorded = usesDatabase(m) ? db_.learn(m) : std::nullopt;
      if (!recorded || *recorded == o_.learn) continue;
      throw InputError(o_.results, "--learn",
                       "its " + m + " trials ran with " + learnText(*recorded) + "; this run gives " +
                           learnText(o_.learn) +
                           ": a results file holds one --learn setting per method (give the same, or another "
                           "--results)");
    }
  }

  // The families of robots (mobile, arms) whose E-ARC databases this
  // run's earc trials use.
  std::set<std::string> families() const { return runFamilies(o_, files_); }

  // The family of a recorded trial: its suite's, or its scenario file's
  // when that is one of this run's files; nothing for another file.
  std::optional<std::string> familyOf(const TrialRecord& t) const {
    if (t.suite != kFilesSuite) return suiteByName(t.suite).family;
    for (const ScenarioFile& f : files_)
      if (f.path == t.scenario_file) return f.family;
    return std::nullopt;
  }

  // The earc trials of one family of robots and one --seed plan with one
  // E-ARC database, as they found it: a resumed run on another would put
  // trials of two databases in one cell. (Another seed's is another: the
  // run builds one per seed, as it draws other scenarios per seed.) "The
  // same" is the same file wherever it lies now (moved or copied, given
  // by another path) and changed since only by the trials' own learning
  // (--learn): the token of the last line of its history, which each earc
  // trial records, is still in its history, and no line after it added
  // or removed rows but those. Another database, built again in its place
  // (even by the same command: what it holds depends on the earc build
  // too), curated or added to since, or one this run would build because
  // it is gone (or because the trials ran on one named as before
  // earcDbPath's names), is refused before anything runs. Files from
  // before schema 8, and databases without a history (experience schema
  // before 5), have none to tell by.
  void requireSameEarcDb() const {
    if (!runs("earc")) return;
    const std::set<std::string> ours = families();
    std::set<std::pair<std::string, std::int64_t>> checked;
    for (const TrialRecord& t : db_.recordedTrials()) {
      if (t.method != "earc" || !t.earc_db_state || t.seed != o_.seed) continue;
      const auto family = familyOf(t);
      if (!family || !ours.count(*family) || !checked.insert({*family, *t.earc_db_state}).second) continue;
      const std::string path = earcDb(*family);
      const auto refuse = [&](const std::string& now) {
        return InputError(o_.results, "--db-" + *family,
                          "its earc trials of " + (*family == "arms" ? std::string("arms") : *family + " robots") +
                              " with --seed " + std::to_string(o_.seed) + " ran on the E-ARC database " + t.earc_db +
                              "; " + now +
                              ": a results file holds the earc trials of one E-ARC database per kind of robot and "
                              "seed, as they found it (give that one, or another --results)");
      };
      const auto facts = existing_.find(*family);
      if (facts == existing_.end()) throw refuse("this run would build a new one at " + path);
      const std::vector<exp::HistoryLine>& lines = facts->second.history;
      if (lines.empty()) continue;
      const auto then = std::find_if(lines.begin(), lines.end(),
                                     [&](const exp::HistoryLine& l) { return l.token == *t.earc_db_state; });
      if (then == lines.end()) throw refuse(path + " is another");
      std::vector<std::string> changes;
      for (auto l = then + 1; l != lines.end(); ++l)
        if ((l->rows_added || l->rows_removed) && !(o_.learn && l->operation == "learn") &&
            std::find(changes.begin(), changes.end(), l->operation) == changes.end())
          changes.push_back(l->operation);
      if (changes.empty()) continue;
      std::string what;
      for (const std::string& c : changes) what += (what.empty() ? "" : ", ") + c;
      throw refuse(path + " has changed since (" + what + ")");
    }
  }

  // The E-ARC databases runs built into this file (databases rows with a
  // construction time, which have recorded the count since schema 1) were
  // built from one --earc-db-count: a run that builds its own from another
  // (by its name, another database; for another --seed too) would put
  // trials of databases built from two counts in one cell, as other
  // Lightning settings would. A database given (--db-mobile) is used as it
  // is, and no count goes with it.
  void requireSameEarcDbCount() const {
    if (!runs("earc")) return;
    const std::vector<DatabaseRecord> recorded = db_.databases();
    const auto count = [](std::optional<std::int64_t> n) {
      return n ? std::to_string(*n) + " problems" : std::string("earc-db's default count");
    };
    const std::optional<std::int64_t> given = o_.earc_db_count;
    for (const std::string& family : families()) {
      if (!(family == "arms" ? o_.db_arms : o_.db_mobile).empty()) continue;
      // Scenario files' rows are of suite files, whichever their kind: a
      // cell pools the files of one robot count, mobile or arms.
      const std::string suite = files_.empty() ? family : std::string(kFilesSuite);
      for (const DatabaseRecord& d : recorded) {
        if (d.method != "earc" || d.suite != suite || !d.construction_time_s || d.problems == given) continue;
        throw InputError(o_.results, "--earc-db-count",
                         "its E-ARC database " + d.path + " was built from " + count(d.problems) +
                             "; this run gives " + count(given) +
                             ": a results file holds the earc trials of E-ARC databases built from one count (give "
                             "the same, or another --results)");
      }
    }
  }

  // A scenario file's trials are numbered by the order the files were
  // given in: a resumed run given other files, or the same in another
  // order, would skip trials recorded for other scenarios. The hash of
  // each file's scenario is recorded as its trials' scenario seed.
  void requireSameFiles() const {
    if (files_.empty()) return;
    const TrialFilter f{o_.seed, o_.time_limit_s};
    for (const TrialRecord& t : f.apply(db_.recordedTrials())) {
      if (t.suite != kFilesSuite) continue;
      for (const ScenarioFile& file : files_)
        if (file.robots() == t.robots && file.trial == t.trial && file.hash != t.scenario_seed)
          throw InputError(o_.results, "",
                           "its trial " + std::string(kFilesSuite) + "-" + std::to_string(t.robots) + "-t" +
                               std::to_string(t.trial) + " (" + t.method + ") was planned on another scenario than " +
                               file.path + ", the " + ordinal(file.trial + 1) + " file of " +
                               std::to_string(t.robots) +
                               " robots given: give the files as before, or another --results");
    }
  }

  static std::string ordinal(int n) {
    const int tens = n % 100, ones = n % 10;
    const char* suffix = tens >= 11 && tens <= 13 ? "th" : ones == 1 ? "st" : ones == 2 ? "nd" : ones == 3 ? "rd" : "th";
    return std::to_string(n) + suffix;
  }

  RunSummary finishInterrupted() {
    summary_.interrupted = true;
    log_ << "interrupted: " << summary_.run << " trials recorded in " << o_.results
         << "; run the same command again to resume\n";
    return summary_;
  }

  std::vector<Cell> pending() {
    const auto done = db_.finishedTrials(o_.seed, o_.time_limit_s);
    std::vector<Cell> cells;
    // Scenario files: the methods take turns file by file (with several
    // jobs, each method's files in a row), as in a suite's cell.
    for (const ScenarioFile& f : files_)
      for (const std::string& m : o_.methods) {
        ++summary_.cells_total;
        if (done.count({kFilesSuite, f.robots(), m, f.trial})) {
          ++summary_.skipped;
          continue;
        }
        cells.push_back({nullptr, f.robots(), f.trial, m, &f});
      }
    if (o_.jobs > 1)
      std::stable_sort(cells.begin(), cells.end(),
                       [&](const Cell& a, const Cell& b) { return methodIndex(a.method) < methodIndex(b.method); });
    if (!files_.empty()) return cells;
    for (const std::string& name : o_.suites) {
      const Suite& s = suiteByName(name);
      for (int n : suiteCounts(s, o_.robots)) {
        // One job: the methods take turns trial by trial, so that a drift
        // of the machine's speed touches every method alike. Several
        // jobs: each method's trials of this cell in a row, so that trials
        // side by side are of one method. Side by side, E-ARC's and ARC's
        // trials of one scenario started together, and E-ARC's start-up
        // (reading its database) ran beside ARC's planning: at 16 arms
        // ARC's median rose by a third, E-ARC's by a tenth.
        const std::size_t before = cells.size();
        for (int trial = 0; trial < o_.trials; ++trial)
          for (const std::string& m : o_.methods) {
            ++summary_.cells_total;
            if (done.count({s.name, n, m, trial})) {
              ++summary_.skipped;
              continue;
            }
            cells.push_back({&s, n, trial, m});
          }
        if (o_.jobs > 1)
          std::stable_sort(cells.begin() + static_cast<std::ptrdiff_t>(before), cells.end(),
                           [&](const Cell& a, const Cell& b) { return methodIndex(a.method) < methodIndex(b.method); });
      }
    }
    return cells;
  }

  std::size_t methodIndex(const std::string& m) const {
    return static_cast<std::size_t>(std::find(o_.methods.begin(), o_.methods.end(), m) - o_.methods.begin());
  }

  // The problems a Lightning database for this many robots is grown from.
  int lightningProblems(int robots) const {
    return o_.lightning_problems.value_or(o_.lightning_problems_per_robot * robots);
  }

  // A suite's per robot count; a scenario file's per world (files that
  // differ only in starts and goals share it). The name also says how it
  // grows: from how many problems, each under what limit, of which seed,
  // and whether trials add to it (--learn). A database is used only by
  // runs that would grow it so, never found again by a run with other
  // settings or another seed (a resumed file from before schema 7,
  // another --results sharing the --lightning-dir) and taken as theirs.
  std::string lightningDb(const Cell& c) const {
    std::string name = c.file ? std::string(kFilesSuite) : c.suite->name;
    name += "-" + std::to_string(c.robots);
    if (c.file) name += "-" + hex16(c.file->world);
    name += "-p" + std::to_string(lightningProblems(c.robots)) + "-t" +
            exactNumber(o_.lightning_problem_time_limit_s) + "-s" + std::to_string(o_.seed);
    if (o_.learn) name += "-learn";
    return lightning_dir_ + "/" + name + ".lightning";
  }

  // earcDbPath's, worked out once per family.
  const std::string& earcDb(const std::string& family) const { return earc_dbs_.at(family); }

  // One line for a database whose build (a child, logs at STEM.out and
  // .err) failed; the method's trials then fail with its planner's own
  // message about the file.
  static void buildFailed(const std::string& path, const ChildOutcome& out, const std::string& stem,
                          std::string_view method) {
    // Stopped by Ctrl-C (or SIGTERM): the run says it was interrupted.
    if (interruptFlag().load()) return;
    std::cerr << "earc-bench: building " << path << " failed (" << exitDescription(out)
              << "): " << lastLine(stem + ".err") << "; its " << method << " trials will fail\n";
  }

  // A Lightning database is built (in a child, timed) just before the
  // first trial that needs it, so that trials --cutoff skips never pay for
  // one (at 32 robots that is minutes of planning problems it cannot
  // solve). One build at a time; other workers wait for theirs.
  void ensureLightningDb(const Cell& c) {
    std::lock_guard lock(lightning_mutex_);
    if (interruptFlag().load()) return;
    const int robots = c.robots;
    const std::string path = lightningDb(c);
    if (fs::exists(path)) return;
    fs::create_directories(lightning_dir_);
    const int problems = lightningProblems(robots);
    log_ << "building Lightning database " << path << " from " << problems << " problems\n";
    log_.flush();
    std::vector<std::string> argv = {bench_, "lightning-db"};
    if (c.file) {
      argv.insert(argv.end(), {"--scenario", scenarioFile(c)});
    } else {
      argv.insert(argv.end(), {"--suite", c.suite->name, "--robots", std::to_string(robots)});
    }
    argv.insert(argv.end(), {"--count", std::to_string(problems), "--seed", std::to_string(o_.seed),
                             "--problem-time-limit", exactNumber(o_.lightning_problem_time_limit_s), "-o", path,
                             "--results", o_.results});
    const std::string stem = work_ + "/logs/lightning-db-" + fs::path(path).stem().string();
    ChildSpec spec;
    spec.argv = argv;
    spec.stdout_path = stem + ".out";
    spec.stderr_path = stem + ".err";
    spec.wall_limit_s =
        problems * (o_.lightning_problem_time_limit_s + wallMargin(o_.lightning_problem_time_limit_s)) + 60.0;
    spec.memory_limit_mb = o_.memory_limit_mb;
    ChildOutcome out = runChild(spec, &interruptFlag());
    if (out.exit_code != 0) {
      buildFailed(path, out, stem, "Lightning");
      return;
    }
    // What the minutes bought: entries, and how many problems it solved
    // (none, for robots too many for it: its trials then plan from scratch).
    log_ << "  " << lastLine(stem + ".out") << "\n";
    log_.flush();
  }

  // Databases are built (in a child, timed) when missing and recorded in
  // the results with their construction time; a database that was given
  // is recorded without one.
  void prepareDatabases(const std::vector<Cell>& cells) {
    std::set<std::string> families;
    for (const Cell& c : cells)
      if (c.method == "earc") families.insert(c.family());
    for (const std::string& family : families) {
      if (interruptFlag().load()) return;
      const std::string path = earcDb(family);
      std::optional<double> construction;
      if (!exp::isPostgresLocation(path) && !fs::exists(path)) {
        construction = buildEarcDb(family, path);
        if (!construction) continue;
      }
      warnNoClassFits(family, path);
      if (!construction && db_.hasDatabase("earc", path)) continue;
      DatabaseRecord d;
      d.method = "earc";
      d.suite = files_.empty() ? family : kFilesSuite;
      d.robots = 0;
      d.path = path;
      d.construction_time_s = construction;
      d.size_bytes = exp::isPostgresLocation(path)
                         ? 0
                         : fileSize(path) + std::max<std::int64_t>(0, fileSize(exp::databaseFile(path) + "-wal"));
      if (construction) {
        d.seed = o_.seed;
        if (o_.earc_db_count) d.problems = *o_.earc_db_count;
      }
      // One built here is new: opened now, for the first time.
      const auto checked = existing_.find(family);
      const EarcDbFacts facts =
          construction || checked == existing_.end() ? earcDbFacts(o_, files_, family) : checked->second;
      d.entries = facts.entries;
      earc_states_[family] = earcDbState(facts);
      db_.addDatabase(d);
    }
  }

  // A database given for scenario files (--db-mobile, --db-arms) may hold
  // nothing for their robots: E-ARC then plans as ARC, which a table would
  // not show. Said once per robot geometry (and arm layout), as earc-plan
  // says it.
  void warnNoClassFits(const std::string& family, const std::string& path) {
    if (files_.empty()) return;
    std::optional<exp::ExperienceStore> store;
    try {
      exp::StoreOptions so;
      so.read_only = true;
      so.new_session = false;
      store.emplace(path, so);
    } catch (const std::exception&) {
      return;  // the trials say what is wrong with it
    }
    std::set<std::string> said;
    for (const ScenarioFile& f : files_)
      if (f.family == family && said.insert(earcBuildKey(f)).second) {
        std::string w = unbuildableReason(f);
        if (!w.empty())
          w += ": an E-ARC database holds nothing for these arms, and E-ARC plans as ARC does";
        else
          w = exp::noClassFitsWarning(*store, f.scenario, path);
        if (!w.empty()) std::cerr << "earc-bench: warning: " << printableText(f.path + ": " + w, 4096) << "\n";
      }
  }

  // Runs `earc-db build` for one family; its wall time is the construction
  // time (nullopt when it failed: the earc trials then fail with
  // earc-plan's own message about the database).
  // Scenario files: one build per robot geometry (and arm layout) among
  // the family's files, into the one database; the construction time is
  // their sum.
  std::optional<double> buildEarcDb(const std::string& family, const std::string& path) {
    const std::string program = o_.earc_db_program.empty() ? executableDir() + "/earc-db" : o_.earc_db_program;
    std::vector<std::pair<std::string, std::string>> builds;  // (how, log stem)
    if (files_.empty()) {
      builds.push_back({"--kind=" + family, work_ + "/logs/earc-db-" + family});
    } else {
      // Not an arm layout with no pair the database can hold
      // (warnNoClassFits says why): failing its build would take the
      // other files' rows and E-ARC trials with it.
      for (const ScenarioFile* f : earcBuildFiles(files_, family))
        builds.push_back({"--scenario=" + scenarioFile(*f),
                          work_ + "/logs/earc-db-" + family + "-" + std::to_string(builds.size())});
      // Every layout unbuildable: an empty database, which E-ARC opens.
      if (builds.empty()) exp::ExperienceStore created(path);
    }
    double construction = 0;
    for (const auto& [how, stem] : builds) {
      if (interruptFlag().load()) break;
      log_ << "building E-ARC database " << path << " (earc-db build " << how << ")\n";
      log_.flush();
      ChildSpec spec;
      spec.argv = {program, "build", "--db", path, how, "--seed", std::to_string(o_.seed)};
      if (o_.earc_db_count) {
        spec.argv.push_back("--count");
        spec.argv.push_back(std::to_string(*o_.earc_db_count));
      }
      spec.stdout_path = stem + ".out";
      spec.stderr_path = stem + ".err";
      spec.wall_limit_s = kEarcDbWallLimitS;
      spec.memory_limit_mb = o_.memory_limit_mb;
      ChildOutcome out = runChild(spec, &interruptFlag());
      if (out.exit_code != 0) {
        buildFailed(path, out, stem, "earc");
        // A half-built database must not pass for a built one: the file
        // (a link's target: the link was given) and its -wal and -shm.
        exp::removeDatabaseFiles(exp::databaseFile(path));
        return std::nullopt;
      }
      construction += out.wall_s;
    }
    return construction;
  }

  TrialSeeds seedsOf(const Cell& c) const {
    return c.file ? fileTrialSeeds(*c.file, o_.seed) : trialSeeds(*c.suite, c.robots, c.trial, o_.seed);
  }

  // The trial's scenario in WORK/scenarios, written once: a suite's
  // generated, a file's copied as it was read.
  std::string scenarioFile(const Cell& c) {
    const std::string path = work_ + "/scenarios/" + c.trialName() + "-" + hex16(seedsOf(c).scenario) + ".json";
    std::lock_guard lock(scenario_mutex_);
    if (!fs::exists(path))
      writeTextFileAtomic(path, scenarioToJson(c.file ? c.file->scenario : trialScenario(*c.suite, c.robots, c.trial, o_.seed))
                                        .dump(1) + "\n");
    return path;
  }
  std::string scenarioFile(const ScenarioFile& f) { return scenarioFile(Cell{nullptr, f.robots(), f.trial, "", &f}); }

  std::vector<std::string> planArgv(const Cell& c, const std::string& scenario, const std::string& solution,
                                    std::uint64_t seed) const {
    const std::string db = c.method == "earc"        ? earcDb(c.family())
                           : c.method == "lightning" ? lightningDb(c)
                                                     : std::string();
    return bench::planArgv({plan_, scenario, solution, c.method, o_.time_limit_s, seed, db, o_.learn, argsOf(c.method)});
  }

  // The trial's figures from a solution readPlanSolution accepted; its
  // solved flag.
  static bool readStats(const nlohmann::json& doc, TrialRecord& t) {
    const bool database_method = usesDatabase(t.method);
    const bool solved = doc["solved"].get<bool>();
    const nlohmann::json st = doc.value("stats", nlohmann::json::object());
    // Another program's output (--plan-program): a figure the results
    // reader would refuse (negative, fractional, not finite) is left out
    // rather than stored, where it would make the whole file unreadable.
    auto num = [&](const char* key) -> std::optional<std::int64_t> {
      const auto v = st.find(key);
      // JSON's whole numbers of 0 and more are read as unsigned.
      if (v != st.end() && v->is_number_unsigned() &&
          v->get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
        return v->get<std::int64_t>();
      return std::nullopt;
    };
    if (st.contains("planning_time_s") && st["planning_time_s"].is_number() &&
        std::isfinite(st["planning_time_s"].get<double>()) && st["planning_time_s"].get<double>() >= 0)
      t.planning_time_s = st["planning_time_s"].get<double>();
    t.makespan = num("makespan");
    t.sum_of_costs = num("sum_of_costs");
    t.conflicts = num("conflicts");
    readRefineStats(st, t);
    t.planner_version = plannerVersion(doc);
    // E-ARC's database answers, retrieved as they are or repaired, as its
    // summary line and db_hit_rate count them (its db_hits stat counts the
    // former only); Lightning's: 1 when it recalled the whole problem.
    if (database_method)
      t.db_hits = st.contains("subproblems_by_solver") ? std::optional<std::int64_t>(databaseAnswers(st).answered())
                                                        : num("db_hits");
    if (t.db_hits && *t.db_hits < 0) t.db_hits.reset();
    if (!solved && st.contains("failure")) {
      const std::string why = failureReasons(st);
      t.failure = "not solved: " + (why.empty() ? std::string("no reason given") : why);
      // What was wrong with a result the planner refused (the validator's
      // violations, or Lightning's own motion check).
      if (st.contains("invalid_result") && st["invalid_result"].is_array() && !st["invalid_result"].empty() &&
          st["invalid_result"][0].is_string())
        t.failure += " (" + st["invalid_result"][0].get<std::string>() + ")";
    }
    return solved;
  }

  TrialRecord runTrial(const Cell& c) {
    TrialRecord t;
    t.suite = c.suiteName();
    t.robots = c.robots;
    t.method = c.method;
    t.trial = c.trial;
    t.seed = o_.seed;
    t.time_limit_s = o_.time_limit_s;
    t.jobs = o_.jobs;
    t.bench_version = earc::version();
    t.planner_args = argsOf(c.method);
    if (c.file) t.scenario_file = c.file->path;
    if (c.method == "lightning") t.lightning = lightningSettings();
    if (usesDatabase(c.method)) t.learn = o_.learn;
    if (c.method == "earc") {
      t.earc_db = earcDb(c.family());
      const auto state = earc_states_.find(c.family());
      if (state != earc_states_.end()) t.earc_db_state = state->second;
    }
    const TrialSeeds seeds = seedsOf(c);
    t.scenario_seed = seeds.scenario;
    t.planner_seed = seeds.planner;
    if (c.suite) t.lower_bound = suiteLowerBound(*c.suite, c.robots);
    std::string scenario;
    try {
      scenario = scenarioFile(c);
    } catch (const std::exception& e) {
      t.failure = std::string("scenario generation failed: ") + e.what();
      return t;
    }
    const std::string stem = c.trialName() + "-" + c.method;
    const std::string solution = work_ + "/solutions/" + stem + ".json";
    const std::string out = work_ + "/logs/" + stem + ".out", err = work_ + "/logs/" + stem + ".err";
    fs::remove(solution);
    ChildSpec spec;
    spec.argv = planArgv(c, scenario, solution, seeds.planner);
    spec.stdout_path = out;
    spec.stderr_path = err;
    spec.wall_limit_s = o_.time_limit_s + o_.wall_margin_s.value_or(wallMargin(o_.time_limit_s));
    spec.memory_limit_mb = o_.memory_limit_mb;
    spec.fault = faultFor(c.method);
    ChildOutcome run = runChild(spec, &interruptFlag());
    t.wall_time_s = run.wall_s;
    t.peak_memory_kb = run.peak_rss_kb;
    t.exit_status = run.exit_code;
    t.term_signal = run.signal;
    t.failure = childFailure(run, spec, err);
    // Refused for its --method-arg (or anything else that is not this
    // scenario's): every trial of the method would be, and recorded they
    // would be skipped when the run is resumed with the options mended.
    if (!t.planner_args.empty() && refusedItsCommand(run, t.failure, scenario))
      throw InputError(plan_, "--method-arg " + c.method,
                       "refused " + c.method + "'s trial " + c.trialName() + " run" + withArgs(t.planner_args) + ", so would every " +
                           c.method + " trial (not recorded): " + t.failure);
    if (t.failure.empty()) {
      nlohmann::json doc;
      if (auto why = readPlanSolution(run, solution, err, doc))
        t.failure = *why;
      else if (readStats(doc, t))
        validate(c, scenario, solution, stem, t);
      else if (t.failure.empty())
        t.failure = "not solved";
    }
    if (t.success) {
      if (!o_.keep_solutions) fs::remove(solution);
      fs::remove(out);
      fs::remove(err);
    }
    return t;
  }

  void validate(const Cell& c, const std::string& scenario, const std::string& solution, const std::string& stem,
                TrialRecord& t) {
    const auto why = validateSolution(plan_, scenario, solution, work_ + "/logs/" + stem, o_.memory_limit_mb);
    if (!why) {
      if (t.planning_time_s && *t.planning_time_s > o_.time_limit_s * kSolvedTimeLimitSlack) {
        t.failure = "solved after the time limit (" + fmtSeconds(*t.planning_time_s) + " s)";
        return;
      }
      t.success = true;
      return;
    }
    if (*why == "interrupted") {
      t.failure = *why;
      return;
    }
    t.failure = "invalid solution: " + *why;
    {
      std::lock_guard lock(record_mutex_);
      ++summary_.invalid;
    }
    std::cerr << "INVALID SOLUTION: " << (c.file ? c.file->path : c.suiteName()) << ", " << c.robots
              << " robots, method " << c.method
              << ", trial " << c.trial << ": " << *why << " (scenario " << scenario << ", solution " << solution
              << ")\n";
  }

  // RunOptions::cutoff: true (and counted) when c's method solved none of
  // the run's trials at a smaller robot count of c's suite.
  // When a smaller count of c's suite and method has solved nothing so far
  // and still has trials running (another worker's), waits for them: the
  // verdict needs them all. Otherwise c counts as running until done(c).
  bool cutOff(const Cell& c) {
    std::unique_lock lock(record_mutex_);
    if (!outcomes_loaded_) {
      TrialFilter f{o_.seed, o_.time_limit_s};
      for (const TrialRecord& t : f.apply(db_.trials())) {
        auto& o = outcomes_[{t.suite, t.method, t.robots}];
        ++o.first;
        if (t.success) ++o.second;
      }
      outcomes_loaded_ = true;
    }
    auto undecided = [&] {
      for (const auto& [key, n] : running_) {
        const auto& [suite, method, robots] = key;
        if (n > 0 && suite == c.suiteName() && method == c.method && robots < c.robots && outcomes_[key].second == 0)
          return true;
      }
      return false;
    };
    finished_cv_.wait(lock, [&] { return !undecided() || interruptFlag().load(); });
    for (const auto& [key, o] : outcomes_) {
      const auto& [suite, method, robots] = key;
      if (suite != c.suiteName() || method != c.method || robots >= c.robots) continue;
      if (o.first >= o_.trials && o.second == 0) {
        ++summary_.cut;
        const std::string note = "cut off: " + c.method + " on " + suite + " from " + std::to_string(c.robots) +
                                 " robots (solved 0 of " + std::to_string(o.first) + " at " +
                                 std::to_string(robots) + ")";
        if (std::find(cut_notes_.begin(), cut_notes_.end(), note) == cut_notes_.end()) cut_notes_.push_back(note);
        return true;
      }
    }
    ++running_[{c.suiteName(), c.method, c.robots}];
    return false;
  }

  // c's trial is recorded (or abandoned): wake workers waiting in cutOff.
  void done(const Cell& c) {
    {
      std::lock_guard lock(record_mutex_);
      --running_[{c.suiteName(), c.method, c.robots}];
    }
    finished_cv_.notify_all();
  }

  void record(const TrialRecord& t) {
    std::lock_guard lock(record_mutex_);
    if (outcomes_loaded_) {
      auto& o = outcomes_[{t.suite, t.method, t.robots}];
      ++o.first;
      if (t.success) ++o.second;
    }
    db_.addTrial(t);
    ++summary_.run;
    if (t.success) ++summary_.solved;
    if (o_.verbose) {
      log_ << t.suite << " " << t.robots << " " << t.method << " #" << t.trial << ": "
           << (t.success ? "solved in " + fmtSeconds(t.planning_time_s.value_or(0)) + " s" : t.failure) << "\n";
      log_.flush();
    }
  }

  void printTable() {
    TrialFilter f{o_.seed, o_.time_limit_s};
    std::set<std::string> suites(o_.suites.begin(), o_.suites.end());
    std::set<std::string> methods(o_.methods.begin(), o_.methods.end());
    // Scenario files: the trials of the files given.
    std::set<std::pair<int, int>> given;
    for (const ScenarioFile& file : files_) given.insert({file.robots(), file.trial});
    std::vector<TrialRecord> mine;
    for (TrialRecord& t : db_.trials()) {
      if (!f.matches(t) || !methods.count(t.method)) continue;
      const bool ours = files_.empty() ? suites.count(t.suite) &&
                                             (o_.robots.empty() || std::count(o_.robots.begin(), o_.robots.end(), t.robots)) &&
                                             t.trial < o_.trials
                                       : t.suite == kFilesSuite && given.count({t.robots, t.trial});
      if (ours) mine.push_back(std::move(t));
    }
    log_ << "\n" << markdownTable(mine, db_.databases()) << crowdTable(mine);
  }

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

}  // namespace

double wallMargin(double time_limit_s) { return 15.0 + 0.25 * time_limit_s; }

std::optional<std::string> readPlanSolution(const ChildOutcome& run, const std::string& solution,
                                            const std::string& err_path, nlohmann::json& doc) {
  const int status = run.exit_code.value_or(-1);
  const auto unreadable = [&] {
    return "exit " + std::to_string(status) + " without a readable solution: " + lastLine(err_path);
  };
  try {
    doc = readJsonFile(solution);
  } catch (const std::exception&) {
    return unreadable();
  }
  if (!doc.is_object() || !doc.contains("solved") || !doc["solved"].is_boolean()) return unreadable();
  if (doc["solved"].get<bool>() != (status == 0))
    return "exit status " + std::to_string(status) + " disagrees with the solution's solved flag";
  return std::nullopt;
}

bool refusedItsCommand(const ChildOutcome& run, const std::string& failure, const std::string& scenario_file) {
  return run.started && !run.cancelled && !run.killed_at_limit && !run.signal && run.exit_code == 2 &&
         failure.find(scenario_file) == std::string::npos;
}

std::string plannerVersion(const nlohmann::json& solution) {
  const auto stats = solution.find("stats");
  if (stats == solution.end() || !stats->is_object()) return "";
  const auto v = stats->find("earc_version");
  return v != stats->end() && v->is_string() ? v->get<std::string>() : "";
}

std::string exitDescription(const ChildOutcome& outcome) {
  if (outcome.signal) return signalName(*outcome.signal);
  return "exit " + std::to_string(outcome.exit_code.value_or(-1));
}

std::optional<std::string> validateSolution(const std::string& validator, const std::string& scenario,
                                            const std::string& solution, const std::string& log_stem,
                                            std::size_t memory_limit_mb) {
  const std::string out = log_stem + ".validate.out", err = log_stem + ".validate.err";
  ChildSpec spec;
  spec.argv = {validator, "validate", scenario, solution};
  spec.stdout_path = out;
  spec.stderr_path = err;
  spec.wall_limit_s = kValidateWallLimitS;
  spec.memory_limit_mb = memory_limit_mb;
  ChildOutcome v = runChild(spec, &interruptFlag());
  if (v.cancelled) return "interrupted";
  if (v.exit_code == 0) {
    fs::remove(out);
    fs::remove(err);
    return std::nullopt;
  }
  if (v.exit_code == 1) return firstLine(out);
  if (v.signal) return std::string("the validator crashed: ") + signalName(*v.signal);
  if (v.killed_at_limit) return "the validator did not finish in " + fmtSeconds(kValidateWallLimitS) + " s";
  return "malformed solution: " + lastLine(err);
}

namespace {

// Every option checked before anything is created, run or recorded: a
// configuration error is not a trial failure. Returns the entries of the
// E-ARC databases that exist, which it had to open to check.
ExistingEarcDbs validateOptions(const RunOptions& o, const std::vector<ScenarioFile>& files) {
  // Single numbers were checked as the options were parsed (earc::cli's
  // validators); what is left depends on more than one option or on the
  // machine.
  if (o.memory_limit_mb > (std::numeric_limits<std::size_t>::max() >> 20))
    throw InputError("", "--memory-limit-mb", "too large");
  for (const std::string& m : o.methods)
    if (std::find(allMethods().begin(), allMethods().end(), m) == allMethods().end())
      throw InputError("", "--methods", "unknown method '" + m + "' (" + allMethodsText() + ")");
  std::vector<const Suite*> suites;
  if (!files.empty() && o.cutoff)
    throw InputError("", "--cutoff", "is for suites (robot counts that grow), not scenario files");
  // A database that was given is not the run's to build: one that is there
  // is used as it is, one that is missing is built with earc-db's default
  // count. A count beside it would be ignored for it, silently.
  if (o.earc_db_count && (!o.db_mobile.empty() || !o.db_arms.empty()))
    throw InputError("", "--earc-db-count",
                     "is for the E-ARC databases the run builds itself, and " +
                         std::string(o.db_mobile.empty() ? "--db-arms" : "--db-mobile") +
                         " names one instead (used as it is; built with earc-db's default count when missing): "
                         "give one or the other");
  std::string counts;  // "mobile: 2, 4, 8, 16, 32; arms: 2, 4, 8, 16"
  for (const std::string& name : files.empty() ? o.suites : std::vector<std::string>{}) {
    const Suite& s = suiteByName(name);
    suites.push_back(&s);
    counts += (counts.empty() ? "" : "; ") + suiteCountsText(s);
  }
  // A count no suite runs would make "nothing to run: all 0 trials are in ...".
  for (int n : files.empty() ? o.robots : std::vector<int>{})
    if (std::none_of(suites.begin(), suites.end(), [n](const Suite* s) { return suiteTakes(*s, n); }))
      throw InputError("", "--robots", "no suite of this run has " + std::to_string(n) + " robots (" + counts + ")");
  for (const auto& [method, args] : o.method_args) {
    if (std::find(allMethods().begin(), allMethods().end(), method) == allMethods().end())
      throw InputError("", "--method-arg", "unknown method '" + method + "' (" + allMethodsText() + ")");
    if (std::find(o.methods.begin(), o.methods.end(), method) == o.methods.end())
      throw InputError("", "--method-arg", "method " + method + " is not one of this run's methods (--methods)");
    requirePlannerArgs(args, "--method-arg " + method);
  }
  // E-ARC's database options where they would be ignored: no earc trials,
  // or no robots of that kind.
  const bool runs_earc = std::find(o.methods.begin(), o.methods.end(), "earc") != o.methods.end();
  const std::set<std::string> families = runFamilies(o, files);
  for (const auto& [option, given, family] :
       {std::tuple{"--earc-db-count", o.earc_db_count.has_value(), ""}, std::tuple{"--db-mobile", !o.db_mobile.empty(), "mobile"},
        std::tuple{"--db-arms", !o.db_arms.empty(), "arms"}}) {
    if (!given) continue;
    if (!runs_earc)
      throw InputError("", option, "is for method earc, which this run does not plan with (--methods)");
    if (*family && !families.count(family))
      throw InputError("", option,
                       std::string("this run plans for no ") + (family == std::string("arms") ? "arms" : "mobile robots") +
                           " (its suites or scenario files), so it would not be used");
  }
  if (!o.plan_program.empty()) requireExecutable(o.plan_program, "--plan-program");
  else requireExecutable(executableDir() + "/earc-plan", "--plan-program (default: earc-plan beside earc-bench)");
  ExistingEarcDbs existing;
  if (runs_earc)
    for (const std::string& family : families)
      if (const std::string db = earcDbPath(o, files, family); exp::isPostgresLocation(db) || fs::exists(db))
        existing[family] = earcDbFacts(o, files, family);  // a store on a server is there: used as it is
  return existing;
}

}  // namespace

RunSummary runBenchmark(const RunOptions& options, std::ostream& log) {
  const std::vector<ScenarioFile> files = loadScenarioFiles(options.scenario_files);
  ExistingEarcDbs existing = validateOptions(options, files);
  InterruptGuard guard;
  Runner runner(options, files, std::move(existing), log);
  return runner.run();
}

}  // namespace earc::bench
