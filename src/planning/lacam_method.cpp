// The crowd solver as a whole-problem method (`--method lacam`).
#include <stdexcept>

#include "earc/planning/crowd.hpp"
#include "earc/planning/methods.hpp"

namespace earc {

PlanResult planLacam(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context) {
  Stopwatch clock;
  PlanResult result;
  result.solution.scenario = scenario.name;
  // Budgets within the time limit (the ways' spreading, refinement's
  // share) count work with --deterministic.
  const Deadline deadline =
      Deadline(settings.time_limit_s).withWorkBudgets(settings.work_budgets).stoppedBy(context.stop);
  const CollisionWorld world(scenario);
  const RobotModels robots(scenario);
  std::vector<int> group;
  std::vector<std::vector<double>> starts, goals;
  for (std::size_t r = 0; r < scenario.robots.size(); ++r) {
    if (scenario.robots[r].kind != RobotKind::Mobile) {
      result.failures.insert(FailureCause::InvalidInput);
      result.stats.detail = "robot " + scenario.robots[r].name + " is an arm: lacam plans mobile robots only";
      result.stats.planning_time_s = clock.seconds();
      return result;
    }
    group.push_back(static_cast<int>(r));
    starts.push_back(scenario.robots[r].start);
    goals.push_back(scenario.robots[r].goal);
  }
  // With --refine, most of its time goes to shortening the plan on the
  // roadmap, where a space-time search is cheap next to refinePlan's on
  // the timed paths; refinePlan takes the rest (shortcuts off the axes).
  const double setup_s = clock.seconds();
  CrowdOptions options;
  options.refine_s = settings.post.refine_s;
  options.refine_deadline = &deadline;
  CrowdOutcome out = planCrowd(world, robots.raw, group, starts, goals, deadline, settings.seed, options);
  result.stats.lacam = out.stats;
  if (out.paths) {
    result.solution.solved = true;
    result.solution.paths = std::move(*out.paths);
  } else {
    result.failures.insert(out.timed_out ? FailureCause::TimeLimit : FailureCause::NoIndividualPath);
    result.stats.detail = out.why;
  }
  // With a lattice refinement, the first plan was found before it.
  result.stats.planning_time_s =
      out.stats.lattice_refine ? setup_s + out.stats.first_solution_s.value_or(0.0) : clock.seconds();
  return result;
}

}  // namespace earc
