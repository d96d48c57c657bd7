// plan(): the dispatcher over every method, with the checks, compaction
// and refinement that all of them share.
#include "earc/methods/plan.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "earc/baselines/lightning.hpp"
#include "earc/experience/store.hpp"
#include "earc/methods/database_solver.hpp"
#include "earc/planning/arc.hpp"
#include "earc/planning/compact.hpp"
#include "earc/planning/methods.hpp"
#include "earc/planning/refine.hpp"
#include "earc/planning/roadmap.hpp"
#include "earc/util/format.hpp"
#include "earc/util/random.hpp"
#include "earc/util/version.hpp"
#include "earc/validate/validator.hpp"

namespace earc {

namespace {

// The scalars of every robot's path if each went straight from start to
// goal at the scenario's resolution: a lower bound on what any plan holds.
// (In steps of the distance metric, as a double: a resolution fine
// enough to overflow a step count is simply too large.)
double straightPathScalars(const Scenario& scenario) {
  double total = 0.0;
  for (const auto& model : makeRobotModels(scenario)) {
    const RobotSpec& r = model->spec();
    total += (std::ceil(model->distance(r.start.data(), r.goal.data())) + 1.0) * model->dim();
  }
  return total;
}

// Refuses a scenario too large to hold (PlannerSettings::max_path_scalars).
bool refuseTooLarge(const Scenario& scenario, const PlannerSettings& settings, PlanResult& result) {
  const double need = straightPathScalars(scenario);
  if (need <= static_cast<double>(settings.max_path_scalars)) return false;
  result.failures.insert(FailureCause::TooLarge);
  result.stats.too_large = TooLargeStats{
      need, settings.max_path_scalars,
      "the robots' straight start-to-goal paths alone hold " +
          std::to_string(static_cast<long long>(std::min(need, 9e18))) + " scalars at this resolution (limit " +
          std::to_string(settings.max_path_scalars) + "): coarsen the resolution or split the problem"};
  result.stats.planning_time_s = 0.0;
  return true;
}

// compactPlan on a solved result; its time counts in the planning time.
void compactResult(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context,
                   PlanResult& result) {
  Stopwatch clock;
  std::vector<Path>& paths = result.solution.paths;
  const RobotModels models(scenario);
  const std::size_t makespan = result.solution.makespan(), sum_of_costs = result.solution.sumOfCosts();
  const double spent = result.stats.planning_time_s.value_or(0.0);
  const Deadline deadline = Deadline(std::max(0.0, settings.time_limit_s - spent))
                               .withWorkBudgets(settings.work_budgets)
                               .stoppedBy(context.stop);
  const CollisionWorld world(scenario);
  const CompactReport rep = compactPlan(models.raw, paths, &world, deadline);
  const double s = clock.seconds();
  CompactStats& c = result.stats.compact.emplace();
  c.s = s;
  c.passes = rep.passes;
  c.robots_retimed = rep.robots_retimed;
  c.steps_saved = rep.steps_saved;
  c.states = static_cast<std::int64_t>(rep.states);
  c.interrupted = rep.interrupted;
  c.makespan_before = static_cast<std::int64_t>(makespan);
  c.sum_of_costs_before = static_cast<std::int64_t>(sum_of_costs);
  result.stats.planning_time_s = spent + s;
}

// refinePlan on a validated result (PostPlanSettings::refine_s), within
// the plan's time limit; the refined plan is validated again and kept only
// if it passes. planning_time_s stays the time to the first valid plan;
// "refine" says what refinement did and when (times on the same clock).
void refineResult(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context,
                  PlanResult& result, ValidationReport& report, const ValidatorSettings& vs, double validation_s) {
  Stopwatch clock;
  const double first_s = result.stats.planning_time_s.value_or(0.0);
  const std::vector<Path> first = result.solution.paths;
  const RobotModels models(scenario);
  const CollisionWorld world(scenario);
  const Deadline deadline =
      Deadline(std::max(0.0, settings.time_limit_s - first_s)).withWorkBudgets(settings.work_budgets).stoppedBy(context.stop);
  // The crowd solver spent part of the budget shortening its plan on its
  // roadmap: that part and the plan before it enter the record.
  const std::optional<LacamStats>& lacam = result.stats.lacam;
  double lattice_s = 0.0, lattice_budget_s = 0.0;
  if (lacam && lacam->lattice_refine) {
    lattice_s = lacam->lattice_refine->s.value_or(0.0);
    lattice_budget_s = lacam->lattice_refine->work_s.value_or(lattice_s);
  }
  RefineSettings rs;
  // The refined plan is validated again within the budget: about as long
  // as the first plan's validation took (seconds on a crowd of hundreds).
  // Not with work budgets, whose refined plan may not depend on the clock.
  rs.seconds = std::max(0.0, settings.post.refine_s - lattice_budget_s - (settings.work_budgets ? 0.0 : validation_s));
  rs.seed = splitSeed(settings.seed, 0x7ef1e);
  rs.roadmap_samples = settings.roadmap.samples;
  rs.roadmap_neighbors = settings.roadmap.neighbors;
  rs.roadmap_seed = splitSeed(settings.seed, 1);  // the methods' roadmaps, as a cache keeps them
  rs.roadmap_cache = context.roadmap_cache;
  const double start = first_s + lattice_s + clock.seconds();
  const RefineReport rep = refinePlan(scenario, world, models.raw, result.solution.paths, rs, deadline);
  const auto count = [](std::size_t n) { return static_cast<std::int64_t>(n); };
  RefineStats j;
  j.first_sum_of_costs = count(rep.first_sum_of_costs);
  j.first_makespan = count(rep.first_makespan);
  if (lattice_s > 0 && lacam->first_sum_of_costs && lacam->first_makespan) {
    j.first_sum_of_costs = *lacam->first_sum_of_costs;
    j.first_makespan = *lacam->first_makespan;
    j.history.push_back({first_s, j.first_sum_of_costs, j.first_makespan});
    if (j.first_sum_of_costs != count(rep.first_sum_of_costs) || j.first_makespan != count(rep.first_makespan))
      j.history.push_back({first_s + lattice_s, count(rep.first_sum_of_costs), count(rep.first_makespan)});
  } else {
    j.history.push_back({first_s, count(rep.first_sum_of_costs), count(rep.first_makespan)});
  }
  for (const auto& h : rep.history)
    j.history.push_back({start + h[0], static_cast<std::int64_t>(h[1]), static_cast<std::int64_t>(h[2])});
  const double last_s = j.history.back().s;
  j.first_s = first_s;
  j.final_sum_of_costs = count(rep.final_sum_of_costs);
  j.final_makespan = count(rep.final_makespan);
  j.final_s = rep.history.empty() ? last_s : start + rep.final_s;
  j.budget_s = settings.post.refine_s;
  j.lower_bound = count(rep.lower_bound);
  j.straight_line_bound = count(rep.straight_line_bound);
  j.retimed_steps = count(rep.retimed_steps);
  j.iterations = count(rep.iterations);
  j.shortcut_tries = count(rep.shortcut_tries);
  j.shortcut_improvements = count(rep.shortcut_improvements);
  j.lns_tries = count(rep.lns_tries);
  j.lns_improvements = count(rep.lns_improvements);
  j.lns_failed = count(rep.lns_failed);
  if (!rep.history.empty()) {
    ValidationReport again = validateSolution(scenario, result.solution, vs);
    if (again.valid) {
      report = std::move(again);
    } else {
      // Refinement checks every change it keeps; should the refined plan
      // not validate all the same, the first plan stands, and says so.
      j.rejected = again.violations.empty() ? "invalid" : again.violations.front().detail;
      j.final_sum_of_costs = count(rep.first_sum_of_costs);
      j.final_makespan = count(rep.first_makespan);
      j.final_s = last_s;
      result.solution.paths = first;
    }
  }
  j.seconds_spent = lattice_s + clock.seconds();
  if (lattice_s > 0) j.lattice_s = lattice_s;
  result.stats.refine = std::move(j);
}

}  // namespace

PlanResult plan(const Scenario& scenario, const PlannerSettings& settings, exp::ExperienceStore* store,
                const PlanContext& given) {
  PlanResult result;
  // Refinement replans on the methods' roadmaps: kept from planning when
  // no cache outlives the plan (the same plan either way, RoadmapCache).
  PlanContext context = given;
  std::unique_ptr<RoadmapCache> roadmaps_for_refining;
  if (settings.post.refine_s > 0 && !context.roadmap_cache) {
    roadmaps_for_refining = std::make_unique<RoadmapCache>(std::size_t{256} << 20);
    context.roadmap_cache = roadmaps_for_refining.get();
  }
  if (!refuseTooLarge(scenario, settings, result)) {
    switch (settings.method) {
      case Method::Arc: result = runArc(scenario, settings, context, arcHierarchy(settings.arc)); break;
      case Method::Earc: result = planEarc(scenario, settings, store, context); break;
      case Method::Prioritized: result = planPrioritized(scenario, settings, context); break;
      case Method::Coupled: result = planCoupled(scenario, settings, context); break;
      case Method::Lightning: result = planLightning(scenario, settings, context); break;
      case Method::Lacam: result = planLacam(scenario, settings, context); break;
    }
  }
  result.solution.method = methodName(settings.method);
  result.solution.scenario = scenario.name;
  // An unsolved result may still carry paths (an invalid one is kept for
  // inspection): name them so that it can be written too.
  if (!result.solution.paths.empty()) result.solution.nameRobots(scenario);
  // A fast wrong answer is a wrong answer: nothing is reported solved
  // unless the validator agrees.
  if (result.solution.solved) {
    // Solvers pad every path of a subproblem to its common length (the
    // prioritized baseline: to the whole makespan), which made its sum of
    // costs n x makespan: a robot waiting at its goal is not counted.
    const RobotModels settled(scenario);
    for (std::size_t r = 0; r < result.solution.paths.size() && r < settled.raw.size(); ++r) {
      settleAtGoal(*settled.raw[r], result.solution.paths[r]);
      result.solution.paths[r].dropTrailingWaits();
    }
    ValidatorSettings vs;
    vs.max_listed = 3;
    std::vector<Path> uncompacted;
    if (settings.post.compact) {
      uncompacted = result.solution.paths;
      compactResult(scenario, settings, context, result);
    }
    Stopwatch validation;
    ValidationReport report = validateSolution(scenario, result.solution, vs);
    const double validation_s = validation.seconds();
    if (!report.valid && settings.post.compact) {
      // Compaction keeps a valid plan valid; should it not have, the plan
      // as planned is checked and reported instead, and the stats say so.
      result.stats.compact->rejected = report.violations.empty() ? "invalid" : report.violations.front().detail;
      result.solution.paths = std::move(uncompacted);
      report = validateSolution(scenario, result.solution, vs);
    }
    if (report.valid && settings.post.refine_s > 0)
      refineResult(scenario, settings, context, result, report, vs, validation_s);
    if (!report.valid) {
      result.solution.solved = false;
      result.failures.insert(FailureCause::InvalidResult);
      auto& v = result.stats.invalid_result.emplace();
      for (const auto& x : report.violations) v.push_back(x.detail);
    } else {
      result.stats.makespan = static_cast<std::int64_t>(report.makespan);
      result.stats.sum_of_costs = static_cast<std::int64_t>(report.sum_of_costs);
    }
  }
  if (!result.solution.solved) {
    auto& why = result.stats.failure.emplace();
    for (FailureCause c : result.failures) why.push_back(failureCauseName(c));
  }
  result.stats.method = methodName(settings.method);
  result.stats.seed = settings.seed;
  result.stats.earc_version = version();
  result.solution.stats = result.stats.toJson();
  return result;
}

// The check's verdict names damage best, so it is thrown also when planning
// met the damage first. awaitCheck() also counts the session, a write: one
// lost leaves the plan standing, as a lesson lost in learning does.
PlanResult planThenAwaitCheck(const Scenario& scenario, const PlannerSettings& settings, exp::ExperienceStore& store,
                              const PlanContext& context) {
  try {
    PlanResult planned = plan(scenario, settings, &store, context);
    try {
      store.awaitCheck();
    } catch (const exp::WriteLostError& e) {
      if (!planned.stats.db_learn_error) {
        planned.stats.db_learn_error = oneLine(e.what());
        planned.solution.stats = planned.stats.toJson();
      }
    }
    return planned;
  } catch (const exp::DamagedDatabaseError&) {
    store.awaitCheck();
    throw;
  }
}

}  // namespace earc
