// earc-bench run: the trials a run is missing, run in parallel, recorded
// as they finish, with --cutoff and interrupts.
#include "earc/bench/runner.hpp"

#include "runner_impl.hpp"

namespace earc::bench {

namespace runner {

Runner::Runner(const RunOptions& o, const std::vector<ScenarioFile>& files, ExistingEarcDbs existing, std::ostream& log)
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

RunSummary Runner::run() {
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
  if (cli::stopFlag().load()) return finishInterrupted();
  Progress progress("bench", cells.size());
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (;;) {
      if (cli::stopFlag().load()) return;
      const std::size_t i = next.fetch_add(1);
      if (i >= cells.size()) return;
      const Cell& c = cells[i];
      if (o_.cutoff && cutOff(c)) {
        progress.tick();
        continue;
      }
      if (cli::stopFlag().load()) {
        if (o_.cutoff) done(c);
        return;
      }
      if (c.method == "lightning") ensureLightningDb(c);
      progress.setStatus(c.suiteName() + " " + std::to_string(c.robots) + " " + c.method + " #" +
                         std::to_string(c.trial));
      TrialRecord t = runTrial(c);
      if (cli::stopFlag().load() && !t.success && t.failure.rfind("interrupted", 0) == 0) {
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
        cli::stopFlag().store(true);
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
    cli::stopFlag().store(false);  // the error stopped the run, not a signal
    std::rethrow_exception(error);
  }
  if (cli::stopFlag().load()) return finishInterrupted();
  log_ << "ran " << summary_.run << " trials: " << summary_.solved << " solved";
  if (summary_.invalid) log_ << ", " << summary_.invalid << " INVALID solutions";
  log_ << "\n";
  for (const auto& line : cut_notes_) log_ << line << "\n";
  printTable();
  return summary_;
}

std::string Runner::ordinal(int n) {
  const int tens = n % 100, ones = n % 10;
  const char* suffix = tens >= 11 && tens <= 13 ? "th" : ones == 1 ? "st" : ones == 2 ? "nd" : ones == 3 ? "rd" : "th";
  return std::to_string(n) + suffix;
}

RunSummary Runner::finishInterrupted() {
  summary_.interrupted = true;
  log_ << "interrupted: " << summary_.run << " trials recorded in " << o_.results
       << "; run the same command again to resume\n";
  return summary_;
}

std::vector<Cell> Runner::pending() {
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

std::size_t Runner::methodIndex(const std::string& m) const {
  return static_cast<std::size_t>(std::find(o_.methods.begin(), o_.methods.end(), m) - o_.methods.begin());
}

// RunOptions::cutoff: true (and counted) when c's method solved none of
// the run's trials at a smaller robot count of c's suite.
// When a smaller count of c's suite and method has solved nothing so far
// and still has trials running (another worker's), waits for them: the
// verdict needs them all. Otherwise c counts as running until done(c).
bool Runner::cutOff(const Cell& c) {
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
  finished_cv_.wait(lock, [&] { return !undecided() || cli::stopFlag().load(); });
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

void Runner::done(const Cell& c) {
  {
    std::lock_guard lock(record_mutex_);
    --running_[{c.suiteName(), c.method, c.robots}];
  }
  finished_cv_.notify_all();
}

void Runner::record(const TrialRecord& t) {
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

void Runner::printTable() {
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

}  // namespace runner

RunSummary runBenchmark(const RunOptions& options, std::ostream& log) {
  const std::vector<ScenarioFile> files = loadScenarioFiles(options.scenario_files);
  runner::ExistingEarcDbs existing = runner::validateOptions(options, files);
  cli::StopSignals guard(cli::StopSignals::Repeats::Caught);
  runner::Runner runner(options, files, std::move(existing), log);
  return runner.run();
}

}  // namespace earc::bench
