#include "earc/planning/planner.hpp"

#include <algorithm>
#include <memory>
#include <cmath>
#include <stdexcept>

#include "earc/io/input_error.hpp"
#include "earc/planning/arc.hpp"
#include "earc/planning/compact.hpp"
#include "earc/planning/coupled_solver.hpp"
#include "earc/planning/methods.hpp"
#include "earc/planning/refine.hpp"
#include "earc/planning/roadmap.hpp"
#include "earc/util/random.hpp"
#include "earc/util/version.hpp"
#include "earc/validate/validator.hpp"

namespace earc {

const char* methodName(Method m) {
  switch (m) {
    case Method::Arc: return "arc";
    case Method::Earc: return "earc";
    case Method::Prioritized: return "prioritized";
    case Method::Coupled: return "coupled";
    case Method::Lightning: return "lightning";
    case Method::Lacam: return "lacam";
  }
  return "?";
}

Method methodFromName(const std::string& name) {
  for (Method m : {Method::Arc, Method::Earc, Method::Prioritized, Method::Coupled, Method::Lightning, Method::Lacam})
    if (name == methodName(m)) return m;
  throw std::invalid_argument("unknown method '" + name + "' (arc, earc, prioritized, coupled, lightning, lacam)");
}

const char* failureCauseName(FailureCause c) {
  switch (c) {
    case FailureCause::TimeLimit: return "time_limit";
    case FailureCause::InvalidInput: return "invalid_input";
    case FailureCause::NoIndividualPath: return "no_individual_path";
    case FailureCause::SubproblemUnsolved: return "subproblem_unsolved";
    case FailureCause::InvalidResult: return "invalid_result";
    case FailureCause::TooLarge: return "too_large";
  }
  return "?";
}

std::vector<std::unique_ptr<SubproblemSolver>> arcHierarchy(const ArcSettings& arc) {
  std::vector<std::unique_ptr<SubproblemSolver>> h;
  DecoupledSettings ds;
  ds.parked_detour = arc.hold_parked;
  CoupledSolverSettings cs;
  cs.parked_held = arc.hold_parked;
  h.push_back(std::make_unique<DecoupledSolver>(ds));
  h.push_back(std::make_unique<CoupledSubproblemSolver>(cs));
  return h;
}

PlanResult planPrioritized(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context) {
  Stopwatch clock;
  PlanResult result;
  result.solution.scenario = scenario.name;
  CollisionWorld world(scenario);
  const RobotModels robots(scenario);
  const std::vector<const RobotModel*>& models = robots.raw;
  const Deadline deadline = Deadline(settings.time_limit_s).stoppedBy(context.stop);
  RoadmapSet roadmaps(world, models, settings.roadmap.samples, settings.roadmap.neighbors,
                      splitSeed(settings.seed, 1), deadline);
  if (context.roadmap_cache) roadmaps.useCache(*context.roadmap_cache, scenario);
  // The whole problem as one subproblem: every robot, its real start and
  // goal, the whole space; individual path lengths set the horizon.
  Subproblem sub;
  std::size_t longest = 0;
  for (std::size_t r = 0; r < models.size(); ++r) {
    auto p = individualPath(world, roadmaps, *models[r], static_cast<int>(r), deadline, splitSeed(settings.seed, 100 + r));
    if (!p) {
      result.failures.insert(deadline.expired() ? FailureCause::TimeLimit : FailureCause::NoIndividualPath);
      result.stats.planning_time_s = clock.seconds();
      return result;
    }
    longest = std::max(longest, p->size());
    sub.robots.push_back(static_cast<int>(r));
    sub.starts.push_back(scenario.robots[r].start);
    sub.goals.push_back(scenario.robots[r].goal);
    ConfigBox box;
    models[r]->samplingBounds(world.workspace(), box.lo, box.hi);
    sub.region.push_back(std::move(box));
  }
  sub.workspace_region = world.workspace();
  sub.t_start = 0;
  sub.t_end = longest;
  sub.whole_problem = true;
  std::vector<Path> none(models.size());
  DecoupledSettings ds;
  ds.time_budget_s = settings.time_limit_s;
  ds.max_expansions = 2000000;
  ds.expansions_per_horizon_step = 0;
  ds.max_orders = 1000;
  // The whole plan is one window: a robot may have to wait long for the
  // ones before it (ARC's subproblems take a shorter horizon).
  ds.horizon_windows = DecoupledSettings::kLongHorizonWindows;
  ds.horizon_steps = DecoupledSettings::kLongHorizonSteps;
  ds.avoid_others = false;
  DecoupledSolver solver(ds);
  SolverContext ctx{world, models, roadmaps, none, sub, deadline, splitSeed(settings.seed, 2)};
  SolverOutcome out = solver.solve(ctx);
  if (out.solution) {
    result.solution.solved = true;
    result.solution.paths = std::move(out.solution->paths);
  } else {
    result.failures.insert(deadline.expired() ? FailureCause::TimeLimit : FailureCause::SubproblemUnsolved);
  }
  if (context.roadmap_cache) result.stats.roadmaps_reused = static_cast<std::int64_t>(roadmaps.reused());
  result.stats.planning_time_s = clock.seconds();
  return result;
}

PlanResult planCoupled(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context) {
  Stopwatch clock;
  PlanResult result;
  result.solution.scenario = scenario.name;
  CollisionWorld world(scenario);
  const RobotModels robots(scenario);
  CoupledQuery q;
  q.robots = robots.raw;
  for (std::size_t r = 0; r < robots.raw.size(); ++r) {
    q.starts.push_back(scenario.robots[r].start);
    q.goals.push_back(scenario.robots[r].goal);
  }
  CoupledSettings cs;
  cs.time_limit_s = settings.time_limit_s - clock.seconds();  // the world's setup counts
  cs.within = Deadline().stoppedBy(context.stop);
  auto sol = cs.time_limit_s > 0 ? solveCoupled(world, q, cs, settings.seed) : std::nullopt;
  if (sol) {
    result.solution.solved = true;
    result.solution.paths = std::move(sol->paths);
  } else {
    result.failures.insert(FailureCause::TimeLimit);
  }
  result.stats.planning_time_s = clock.seconds();
  return result;
}

Scenario requireRobots(Scenario scenario, const std::string& source) {
  if (scenario.robots.empty()) throw InputError(source, "$.robots", "empty: no robots to plan for");
  return scenario;
}

}  // namespace earc
