// One trial of a run: its scenario, the plan child, the solution read
// and validated, its figures.

#include "runner_impl.hpp"

#include "earc/planning/plan_stats.hpp"

namespace earc::bench {

namespace runner {

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

TrialSeeds Runner::seedsOf(const Cell& c) const {
  return c.file ? fileTrialSeeds(*c.file, o_.seed) : trialSeeds(*c.suite, c.robots, c.trial, o_.seed);
}

std::string Runner::scenarioFile(const Cell& c) {
  const std::string path = work_ + "/scenarios/" + c.trialName() + "-" + hex16(seedsOf(c).scenario) + ".json";
  std::lock_guard lock(scenario_mutex_);
  if (!fs::exists(path))
    writeTextFileAtomic(path, scenarioToJson(c.file ? c.file->scenario : trialScenario(*c.suite, c.robots, c.trial, o_.seed))
                                      .dump(1) + "\n");
  return path;
}

std::vector<std::string> Runner::planArgv(const Cell& c, const std::string& scenario, const std::string& solution,
                                  std::uint64_t seed) const {
  const std::string db = c.method == "earc"        ? earcDb(c.family())
                         : c.method == "lightning" ? lightningDb(c)
                                                   : std::string();
  return bench::planArgv({plan_, scenario, solution, c.method, o_.time_limit_s, seed, db, o_.learn, argsOf(c.method)});
}

bool Runner::readStats(const nlohmann::json& doc, TrialRecord& t) {
  const bool database_method = usesDatabase(t.method);
  const bool solved = doc["solved"].get<bool>();
  const nlohmann::json st = doc.value("stats", nlohmann::json::object());
  // Another program's output (--plan-program): a figure the results
  // reader would refuse (negative, fractional, not finite) is left out
  // rather than stored, where it would make the whole file unreadable;
  // PlanStats::fromJson leaves out what is not a count already.
  const PlanStats ps = PlanStats::fromJson(st);
  if (ps.planning_time_s && std::isfinite(*ps.planning_time_s) && *ps.planning_time_s >= 0)
    t.planning_time_s = ps.planning_time_s;
  t.makespan = ps.makespan;
  t.sum_of_costs = ps.sum_of_costs;
  if (ps.arc) t.conflicts = ps.arc->conflicts;
  readRefineStats(st, t);
  t.planner_version = plannerVersion(doc);
  // E-ARC's database answers, retrieved as they are or repaired, as its
  // summary line and db_hit_rate count them (its db_hits stat counts the
  // former only); Lightning's: 1 when it recalled the whole problem.
  if (database_method) t.db_hits = ps.arc ? std::optional<std::int64_t>(databaseAnswers(ps).answered()) : ps.db_hits;
  if (!solved && st.contains("failure")) {
    const std::string why = failureReasons(st);
    t.failure = "not solved: " + (why.empty() ? std::string("no reason given") : why);
    // What was wrong with a result the planner refused (the validator's
    // violations, or Lightning's own motion check).
    if (ps.invalid_result && !ps.invalid_result->empty()) t.failure += " (" + ps.invalid_result->front() + ")";
  }
  return solved;
}

TrialRecord Runner::runTrial(const Cell& c) {
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
  ChildOutcome run = runChild(spec, &cli::stopFlag());
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

void Runner::validate(const Cell& c, const std::string& scenario, const std::string& solution, const std::string& stem,
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

}  // namespace runner

double wallMargin(double time_limit_s) { return 15.0 + 0.25 * time_limit_s; }

// A plan child's solution file, read once childFailure has found nothing
// wrong with the child (it exited 0 or 1). Nothing, with `doc` filled,
// when it can be used; else why not, in one line: "exit N without a
// readable solution: <last line of err_path>" (no file, not JSON, no
// boolean "solved"), or "exit status N disagrees with the solution's
// solved flag" (earc-plan exits 0 exactly when it solved).
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

// Whether a plan child refused the command it was given rather than its
// scenario: exit status 2 (earc-plan's bad input: an option it does not
// know or a value it refuses, a database too new for it) with a failure
// (childFailure's line) that does not name the scenario file. Every plan
// given the same options would be refused alike, so compare stops at its
// first plan and run at a trial of a method given --method-arg.
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

// `validator validate SCENARIO SOLUTION` (an earc-plan) in a child, its
// output in LOG_STEM.validate.out and .err (removed when valid): nothing
// when the solution is valid, else why in one line ("interrupted" when
// cli::stopFlag() was raised).
std::optional<std::string> validateSolution(const std::string& validator, const std::string& scenario,
                                            const std::string& solution, const std::string& log_stem,
                                            std::size_t memory_limit_mb) {
  const std::string out = log_stem + ".validate.out", err = log_stem + ".validate.err";
  ChildSpec spec;
  spec.argv = {validator, "validate", scenario, solution};
  spec.stdout_path = out;
  spec.stderr_path = err;
  spec.wall_limit_s = runner::kValidateWallLimitS;
  spec.memory_limit_mb = memory_limit_mb;
  ChildOutcome v = runChild(spec, &cli::stopFlag());
  if (v.cancelled) return "interrupted";
  if (v.exit_code == 0) {
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return std::nullopt;
  }
  if (v.exit_code == 1) return firstLine(out);
  if (v.signal) return std::string("the validator crashed: ") + signalName(*v.signal);
  if (v.killed_at_limit) return "the validator did not finish in " + runner::fmtSeconds(runner::kValidateWallLimitS) + " s";
  return "malformed solution: " + lastLine(err);
}

}  // namespace earc::bench
