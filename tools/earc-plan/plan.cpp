// earc-plan plan: plan a scenario with one method and write its solution.
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <utility>

#include "earc/cli/stop_signals.hpp"
#include "earc/cli/subcommands.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/experience/store.hpp"
#include "earc/io/json_io.hpp"
#include "earc/methods/database_solver.hpp"
#include "earc/methods/options.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/planner.hpp"
#include "earc/scene/pass_through.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/format.hpp"
#include "earc/validate/scenario_check.hpp"
#include "earc/validate/validator.hpp"
#include "plan_store.hpp"

namespace earc {
namespace {

struct PlanOptions {
  std::string scenario;
  std::string output;
  std::string method = "arc";
  std::string db;
  std::string trace;
  double time_limit = 60.0;
  std::uint64_t seed = 1;
  int window = 0;
  bool no_learn = false;
  bool shadow_decoupled = false;
  bool deterministic = false;
  bool compact = false;
  bool no_crowd = false;
  bool retime_windows = false;
  bool restamp_coupled = false;
  double refine = 0.0;
  std::optional<int> db_k, db_repair_max;
  std::optional<double> db_max_stretch;
  std::optional<std::size_t> db_row_cache_mb;
  bool quiet = false;
};

// On a terminal, a plan that takes a while says how far it has got: one
// line on stderr, redrawn in place four times a second from the first half
// second on, and cleared before the summary. Nothing when stderr is not a
// terminal or with -q.
class ProgressLine {
 public:
  ProgressLine(bool enabled, std::string method, double limit_s, int robots, const PlanProgress& progress)
      : method_(std::move(method)), limit_s_(limit_s), robots_(robots), progress_(progress) {
    if (enabled && isatty(STDERR_FILENO)) thread_ = std::thread([this] { run(); });
  }
  ~ProgressLine() { stop(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  void stop() {
    if (!thread_.joinable()) return;
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_one();
    thread_.join();
  }

 private:
  void run() {
    using namespace std::chrono;
    const auto start = steady_clock::now();
    bool drawn = false;
    std::unique_lock lock(mutex_);
    try {
      // After a pause (Ctrl-Z) the next draw is a quarter second on, not a
      // burst of the draws missed.
      for (auto next = start + milliseconds(500); !wake_.wait_until(lock, next, [this] { return stopping_; });
           next = std::max(next + milliseconds(250), steady_clock::now())) {
        const double elapsed = duration<double>(steady_clock::now() - start).count();
        std::fprintf(stderr, "\r%s\033[K", text(elapsed).c_str());
        std::fflush(stderr);
        drawn = true;
      }
    } catch (const std::exception&) {
      // Out of memory for a line of text: the plan matters, the line not.
    }
    if (drawn) std::fputs("\r\033[K", stderr);
  }

  std::string text(double elapsed) const {
    std::string line = "planning (" + method_ + "): " + formatNumber("%.1f", elapsed) + " s of " +
                       formatNumber(limit_s_) + " s";
    const int paths = progress_.individual_paths.load(std::memory_order_relaxed);
    const int conflicts = progress_.conflicts.load(std::memory_order_relaxed);
    if (conflicts > 0) {
      line += ", conflict " + std::to_string(conflicts) + " at step " +
              std::to_string(progress_.conflict_step.load(std::memory_order_relaxed)) + " of " +
              std::to_string(progress_.steps.load(std::memory_order_relaxed)) + ": " +
              std::to_string(progress_.subproblem_robots.load(std::memory_order_relaxed)) + " robots";
      if (const int level = progress_.expansions.load(std::memory_order_relaxed); level > 0)
        line += ", window expanded " + std::to_string(level) + (level == 1 ? " time" : " times");
    } else if (paths > 0) {
      line += ", individual paths " + std::to_string(paths) + " of " + std::to_string(robots_);
    }
    return line;
  }

  const std::string method_;
  const double limit_s_;
  const int robots_;
  const PlanProgress& progress_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;
};

// What --compact changed, after the plan's makespan and sum of costs.
std::string compactSummary(const PlanStats& st) {
  if (!st.compact) return "";
  const CompactStats& c = *st.compact;
  if (c.rejected) return " (compacting made it invalid, so it is as planned: " + *c.rejected + ")";
  return " (before --compact: " + std::to_string(c.makespan_before) + " and " + std::to_string(c.sum_of_costs_before) +
         ")";
}

// What --refine did, after the plan's makespan and sum of costs.
std::string refineSummary(const PlanStats& st) {
  if (!st.refine) return "";
  const RefineStats& r = *st.refine;
  if (r.rejected) return " (the refined plan failed validation, so it is the first plan: " + *r.rejected + ")";
  return " (first plan: " + std::to_string(r.first_makespan) + " and " + std::to_string(r.first_sum_of_costs) +
         "; refined for " + formatNumber("%.2f", r.seconds_spent) + " s)";
}

// What the experience database did in an E-ARC plan, for the summary
// line: "; database answered 6 of 8 solved subproblems (1 by repair), learned 2":
// of the subproblems solved, as db_hit_rate counts them.
std::string databaseSummary(const PlanStats& st) {
  if (!st.db) return "";
  const DatabaseStats& db = *st.db;
  const DatabaseAnswers a = databaseAnswers(st);
  std::string line = "; database answered " + std::to_string(a.answered()) + " of " + std::to_string(a.solved) +
                     " solved subproblems (" + std::to_string(a.repaired) + " by repair), learned " +
                     std::to_string(db.db_learned);
  // Why subproblems solved from scratch were not learned, when some were.
  const std::int64_t unstorable = db.db_learn_unstorable;
  const std::int64_t near_duplicates = st.db_learn_error ? 0 : db.db_learn_candidates - db.db_learned;
  std::vector<std::string> why;
  if (near_duplicates > 0)
    why.push_back(std::to_string(near_duplicates) + " near-duplicate" + (near_duplicates == 1 ? "" : "s"));
  if (unstorable > 0)
    why.push_back(std::to_string(unstorable) + (unstorable == 1 ? " group" : " groups") +
                  " of a kind no class holds (3+ arms, 5+ robots)");
  for (std::size_t i = 0; i < why.size(); ++i) line += (i ? ", " : "; not stored: ") + why[i];
  return line;
}

// The line said after a stop signal, once the solution is written.
std::string interruptedLine(const char* signal_name, const PlanResult& r) {
  std::string line = std::string("earc-plan: interrupted (") + signal_name + "): ";
  if (!r.solution.solved) return line + "planning stopped unsolved, as at the time limit; the solution file says so";
  return line + "planning stopped; the best valid plan found so far is written";
}

int runPlan(const PlanOptions& o) {
  // Ctrl-C (or SIGTERM) stops planning soon instead of ending the process:
  // what was planned is written as at the time limit (see interruptedLine).
  cli::StopSignals signals;
  // Before any planning: no output may overwrite an input or the other
  // output, and each must be writable.
  requireDistinctFiles({{"the scenario", o.scenario}, {"--db", o.db, true}, {"-o", o.output}, {"--trace", o.trace}});
  requireWritableOutput({"-o", o.output});
  requireWritableOutput({"--trace", o.trace});
  // Warnings about the scenario (unknown keys and the like), even with
  // -q: they are about the input, as the pass-through warning is.
  InputWarnings read_warnings;
  Scenario scenario = requireRobots(loadScenario(o.scenario, &read_warnings), o.scenario);
  printInputWarnings(read_warnings);
  if (const std::string line = passThroughWarningLine(scenario, o.scenario, "earc-plan"); !line.empty())
    std::cerr << line << "\n";
  MethodOptions m;
  m.method = o.method;
  m.time_limit = o.time_limit;
  m.seed = o.seed;
  m.db = o.db;
  m.trace = !o.trace.empty();
  if (o.window > 0) m.window = o.window;
  m.learn = !o.no_learn;
  m.deterministic = o.deterministic;
  m.crowd = !o.no_crowd;
  m.compact = o.compact;
  m.retime_windows = o.retime_windows;
  m.restamp_coupled = o.restamp_coupled;
  m.refine = o.refine;
  m.shadow_decoupled = o.shadow_decoupled;
  m.db_k = o.db_k;
  m.db_repair_max = o.db_repair_max;
  m.db_max_stretch = o.db_max_stretch;
  PlannerSettings s = plannerSettingsFor(m, OptionStyle::Cli);
  if (o.db_row_cache_mb && s.method != Method::Earc) throw InputError("", "--db-row-cache-mb", "is for method earc");
  if (s.method == Method::Lightning) {
    if (!o.db.empty() && o.no_learn && !std::filesystem::exists(o.db))
      throw InputError(o.db, "--db", "no such Lightning database (build one with earc-bench lightning-db)");
    // Written after planning: its directory is checked before.
    if (!o.no_learn) requireWritableOutput({"--db", o.db});
  }
  // A disk too full to open the database for learning costs the lesson,
  // not the plan (said after the plan is written).
  std::string full_disk;
  auto store = openStoreForPlanning(s.method, o.db, s.db.learn, rowCacheBytes(o.db_row_cache_mb), &full_disk);
  if (!full_disk.empty()) s.db.learn = false;
  // A database found damaged (by the quick_check that ran while planning,
  // or by a read) is bad input too: one line naming the file, exit 2, no
  // solution written. Busy stays exit 1.
  if (store)
    if (const std::string w = exp::noClassFitsWarning(*store, scenario, o.db); !w.empty())
      std::cerr << "earc-plan: warning: " << printableText(w, 4096) << "\n";
  PlanProgress progress;
  PlanContext context;
  context.progress = &progress;
  context.stop = &signals.flag();
  ProgressLine line(!o.quiet, o.method, o.time_limit, static_cast<int>(scenario.robots.size()), progress);
  PlanResult r = store ? exp::withInputErrors(o.db, [&] { return planThenAwaitCheck(scenario, s, *store, context); })
                       : plan(scenario, s, nullptr, context);
  line.stop();
  // Closed before the plan is saved, so that what it could not write (a
  // full disk) reaches the solution's stats as what learning lost does.
  // Closing here, not in the destructor, keeps it to one line; another
  // error at close (the file found damaged) is a warning, as the
  // destructor's was.
  std::string close_error;
  if (store) {
    try {
      store->close();
    } catch (const exp::WriteLostError& e) {
      if (!r.stats.db_learn_error) r.stats.db_learn_error = oneLine(e.what());
    } catch (const exp::StoreError& e) {
      close_error = oneLine(e.what());
    }
  }
  if (!full_disk.empty()) r.stats.db_learn_error = full_disk;
  const bool interrupted = signals.signal() != 0;
  if (interrupted) r.stats.extra["interrupted"] = signals.signalName();
  r.solution.stats = r.stats.toJson();
  saveSolution(o.output, r.solution);
  // What could not be written to the database is said once, after the
  // plan is saved.
  const std::string learn_error = r.stats.db_learn_error.value_or("");
  if (!o.trace.empty()) writeTextFileAtomic(o.trace, r.trace.dump() + "\n");
  if (!o.quiet) {
    const auto& st = r.stats;
    std::ostream& out = summaryStream({o.output, o.trace});
    if (r.solution.solved)
      out << "solved: " << scenario.robots.size() << " robots, method " << o.method << ", "
          << st.planning_time_s.value_or(0.0) << " s, conflicts " << (st.arc ? st.arc->conflicts : 0)
          << ", makespan " << st.makespan.value_or(0) << ", sum of costs " << st.sum_of_costs.value_or(0)
          << compactSummary(st)
          << refineSummary(st) << databaseSummary(st)
          << "\n";
    else
      out << "not solved (" << earc::failureReasons(r.solution.stats) << ") after "
          << st.planning_time_s.value_or(0.0) << " s" << (st.too_large ? ": " + st.too_large->detail : "") << "\n";
    out << "solution: " << o.output << "\n";
  }
  if (!full_disk.empty())
    std::cerr << "earc-plan: warning: " << printableText(full_disk, 4096) << " (the plan is written)\n";
  else if (!learn_error.empty())
    std::cerr << "earc-plan: warning: " << printableText(learn_error, 4096)
              << " (the plan is written; the database keeps what it had)\n";
  else if (!close_error.empty())
    std::cerr << "earc-plan: warning: closing " << printableText(close_error, 4096) << "\n";
  if (interrupted) {
    std::cerr << interruptedLine(signals.signalName(), r) << "\n";
    return signals.exitCode();
  }
  return r.solution.solved ? 0 : 1;
}

void setupPlan(CLI::App& app) {
  auto opts = std::make_shared<PlanOptions>();
  auto* cmd = app.add_subcommand("plan", "Plan a scenario and write its solution (exit 0 solved, 1 not solved, 130 interrupted)");
  cmd->add_option("scenario", opts->scenario, "Scenario JSON file")->check(earc::cli::kFileName)->required();
  cmd->add_option("-o,--output", opts->output, "Solution JSON file to write")->check(earc::cli::kFileName)->required();
  cmd->add_option("--method", opts->method, "arc, earc, prioritized, coupled, lightning or lacam (crowds)")->capture_default_str();
  cmd->add_option("--db", opts->db,
                  "Experience database (method earc, SQLite); Lightning database (method lightning, OMPL's "
                  "format, created when missing unless --no-learn; without it Lightning starts empty)")
      ->check(earc::cli::kFileName);
  cmd->add_option("--time-limit", opts->time_limit, "Planning time limit in seconds")
      ->check(earc::cli::kFinitePositive)
      ->capture_default_str();
  cmd->add_option("--seed", opts->seed, "Seed for every random choice")->check(earc::cli::kWholeNumber)->capture_default_str();
  cmd->add_option("--trace", opts->trace, "Write a trace of conflicts and subproblems (JSON)")
      ->check(earc::cli::kFileName);
  cmd->add_option("--window", opts->window, "Initial subproblem window in steps each side of a conflict")
      ->check(earc::cli::wholeNumberIn(1, 1000000));
  cmd->add_flag("--no-learn", opts->no_learn, "Leave the database as it is (E-ARC, Lightning)");
  cmd->add_flag("--deterministic", opts->deterministic,
                "ARC, E-ARC: count each solver attempt's budget in work done, not seconds, so that the same "
                "seed gives the same plan on a busy or slower machine (only --time-limit stays wall-clock "
                "time); prioritized and coupled plans are so already; not for lightning");
  cmd->add_flag("--no-crowd", opts->no_crowd,
                "ARC, E-ARC: never hand a jam to the crowd solver (lacam); the methods as published");
  cmd->add_flag("--retime-windows", opts->retime_windows,
                "ARC, E-ARC: retime each mobile robot of a local answer along its route inside its window "
                "before the splice (shorter plans on some worlds, more time; stats window_retimed)");
  cmd->add_flag("--restamp-coupled", opts->restamp_coupled,
                "ARC, E-ARC: time-stamp each coupled answer of mobile robots robot by robot, not in lockstep "
                "(shorter plans, more time; stats coupled_restamped)");
  cmd->add_flag("--compact", opts->compact,
                "After planning, retime every robot along its own route to leave out the waits it does not "
                "need and go at full speed where it crept (any method; shorter plans, same routes; stats "
                "compact; not part of the published methods)");
  cmd->add_option("--refine", opts->refine,
                  "After the first valid plan, spend up to this many seconds (within --time-limit) making it "
                  "shorter: shortcuts and large-neighbourhood search; the best plan found, validated (any "
                  "method; stats refine; default 0: off)")
      ->check(earc::cli::kFiniteNonNegative);
  cmd->add_flag("--shadow-decoupled", opts->shadow_decoupled,
                "E-ARC diagnostic: also run the decoupled solver on every subproblem put to the database and "
                "report what each solved (stats db_shadow_decoupled; planning times then include it)");
  cmd->add_option("--db-k", opts->db_k,
                  "E-ARC: stored solutions retrieved per subproblem, nearest first (default " +
                      std::to_string(PlannerSettings{}.db.k) + ")")
      ->check(earc::cli::wholeNumberIn(1, 1000));
  cmd->add_option("--db-repair-max", opts->db_repair_max,
                  "E-ARC: repair a retrieved solution with at most this many invalid runs of segments; 0: never "
                  "repair (default " + std::to_string(PlannerSettings{}.db.max_invalid_segments) + ")")
      ->check(earc::cli::wholeNumberIn(0, 1000));
  cmd->add_option("--db-max-stretch", opts->db_max_stretch,
                  "E-ARC: refuse a database answer longer than this many times the steps its slowest robot needs "
                  "to go straight from start to goal, and plan that subproblem from scratch (shorter plans for "
                  "arms, slower; default 0: any length)")
      ->check(earc::cli::kFiniteNonNegative);
  addRowCacheOption(*cmd, opts->db_row_cache_mb);
  cmd->add_flag("-q,--quiet", opts->quiet, "Print nothing on success");
  cmd->callback([opts] { cli::setExitCode(runPlan(*opts)); });
}

cli::Registrar registered_plan("earc-plan", "plan", setupPlan);

}  // namespace
}  // namespace earc
