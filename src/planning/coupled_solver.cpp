// Composite-space planning with OMPL's RRT-Connect over OmplComposite (our
// validity, motion checks and seeded sampling; see ompl_composite.hpp).
#include "earc/planning/coupled_solver.hpp"

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "earc/geometry/shapes.hpp"
#include "earc/planning/composite.hpp"
#include "earc/planning/ompl_composite.hpp"
#include "earc/planning/solver.hpp"
#include "earc/util/deadline.hpp"
#include "earc/util/random.hpp"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace earc {

namespace {

// Iterations of random shortcutting applied to a found composite path.
constexpr int kShortcutIterations = 60;

// Iterations of shortcutting on the time-stamped states when polishing
// (on 4,944 stored mobile experiences 400 gave no shorter paths than 100).
constexpr int kStateShortcutIterations = 100;

// Every mobile robot's interior waypoint headings replaced by a steady turn
// from its start heading to its goal heading (by distance travelled; by
// waypoint for a robot that only turns), robot by robot, where the whole
// sequence stays valid.
void turnSteadily(const CompositeChecker& checker, std::vector<CompositeState>& waypoints, const Deadline& deadline) {
  const std::size_t n = waypoints.size();
  if (n < 3) return;
  const auto& robots = checker.robots();
  for (std::size_t r = 0; r < robots.size() && !deadline.expired(); ++r) {
    if (!robots[r]->isMobile()) continue;
    std::vector<double> along(n, 0.0);
    for (std::size_t w = 1; w < n; ++w)
      along[w] = along[w - 1] + std::hypot(waypoints[w][r][0] - waypoints[w - 1][r][0],
                                           waypoints[w][r][1] - waypoints[w - 1][r][1]);
    const double h0 = waypoints.front()[r][2];
    const double turn = geo::angleDiff(h0, waypoints.back()[r][2]);
    std::vector<CompositeState> steady = waypoints;
    for (std::size_t w = 1; w + 1 < n; ++w) {
      const double f = along.back() > 0 ? along[w] / along.back() : static_cast<double>(w) / static_cast<double>(n - 1);
      steady[w][r][2] = geo::wrapAngle(h0 + f * turn);
    }
    bool valid = true;
    // Each state after the first was checked as the end of the motion before.
    for (std::size_t w = 1; w < n && valid; ++w) valid = checker.motionValid(steady[w - 1], steady[w], {.start = w > 1});
    if (valid) waypoints = std::move(steady);
  }
}

// The stream of the planner's sampler (splitSeed of the solve's seed).
constexpr std::uint64_t kSamplerStream = 0x5eed;

// The share of the coupled solver's budget spent first on the robots that
// are not parked, the parked ones held as obstacles.
constexpr double kParkedHeldShare = 0.25;

// The world's workspace and obstacles with `bodies` as obstacles too;
// nothing when one has a shape no obstacle takes (a capsule, a rounded box).
std::optional<Scenario> sceneWith(const CollisionWorld& world, const std::vector<geo::Body>& bodies) {
  Scenario s;
  s.workspace = world.workspace();
  auto add = [&s](const geo::Body& b) {
    if (b.kind == geo::CoreKind::Point)
      s.obstacles.push_back(Obstacle::makeCircle(b.p0, b.radius));
    else if (b.kind == geo::CoreKind::Rect && b.radius == 0.0)
      s.obstacles.push_back(Obstacle::makeBox(b.p0, b.half * 2.0, std::atan2(b.axis.y, b.axis.x)));
    else
      return false;
    return true;
  };
  for (std::size_t i = 0; i < world.obstacleCount(); ++i)
    if (!add(world.obstacle(i))) return std::nullopt;
  for (const geo::Body& b : bodies)
    if (!add(b)) return std::nullopt;
  return s;
}

}  // namespace

LocalSolution timeStampComposite(const std::vector<const RobotModel*>& robots,
                                 const std::vector<std::vector<std::vector<double>>>& waypoints) {
  LocalSolution sol;
  for (const RobotModel* m : robots) sol.paths.emplace_back(m->dim());
  if (waypoints.empty()) return sol;
  for (std::size_t r = 0; r < robots.size(); ++r) sol.paths[r].push(waypoints[0][r].data());
  std::vector<double> q;
  for (std::size_t w = 1; w < waypoints.size(); ++w) {
    int n = compositeSteps(robots, waypoints[w - 1], waypoints[w]);
    for (int k = 1; k <= n; ++k) {
      double s = static_cast<double>(k) / n;
      for (std::size_t r = 0; r < robots.size(); ++r) {
        q.resize(static_cast<std::size_t>(robots[r]->dim()));
        if (k == n)
          q = waypoints[w][r];
        else
          robots[r]->interpolate(waypoints[w - 1][r].data(), waypoints[w][r].data(), s, q.data());
        sol.paths[r].push(q.data());
      }
    }
  }
  return sol;
}

// Makes a valid composite waypoint sequence shorter in steps, keeping it
// valid: every mobile robot turns steadily from its start heading to its
// goal heading along the way, where that stays valid (RRT-Connect's
// waypoints carry random headings, and turning on the spot costs steps);
// then the sequence is shortcut, time-stamped, and shortcut again state by
// state, which removes waits and detours between waypoints. The ends are
// kept. Stops early at the deadline.
void polishComposite(const CompositeChecker& checker, std::vector<CompositeState>& waypoints, std::mt19937_64& rng,
                     const Deadline& deadline) {
  turnSteadily(checker, waypoints, deadline);
  shortcutComposite(checker, waypoints, kShortcutIterations, rng, deadline);
  const LocalSolution stamped = timeStampComposite(checker.robots(), waypoints);
  std::vector<CompositeState> states;
  states.reserve(stamped.length());
  for (std::size_t t = 0; t < stamped.length(); ++t) states.push_back(stateAt(stamped.paths, t));
  shortcutComposite(checker, states, kStateShortcutIterations, rng, deadline);
  waypoints = std::move(states);
}

std::vector<StepRun> invalidRuns(const CompositeChecker& checker, const std::vector<Path>& paths) {
  std::vector<StepRun> runs;
  const std::size_t n = paths.front().size();
  std::vector<char> state_ok(n);
  for (std::size_t t = 0; t < n; ++t) state_ok[t] = checker.stateValid(stateAt(paths, t));
  for (std::size_t t = 0; t + 1 < n; ++t) {
    bool ok = state_ok[t] && state_ok[t + 1] &&
              checker.motionValid(stateAt(paths, t), stateAt(paths, t + 1), {.start = true, .end = true});
    if (ok) continue;
    if (!runs.empty() && runs.back().second + 1 == t)
      runs.back().second = t;
    else
      runs.emplace_back(t, t);
  }
  return runs;
}

// Time-stamped paths with each invalid run replanned in the composite space
// (solveCoupled inside `region`, at most time_per_run_s each and within the
// deadline) between the valid states around it, the rest kept as it was.
// Without paths when a run could not be replanned; `why` says so.
RunRepair repairRuns(const CollisionWorld& world, const std::vector<const RobotModel*>& robots,
                     const std::vector<Path>& paths, const std::vector<StepRun>& runs,
                     const std::vector<ConfigBox>& region, double time_per_run_s, const Deadline& deadline,
                     std::uint64_t seed) {
  std::vector<Path> repaired;
  for (const RobotModel* m : robots) repaired.emplace_back(m->dim());
  std::size_t copied_to = 0;  // states [0, copied_to) of paths are in `repaired`
  for (const auto& [first, last] : runs) {
    const std::size_t a = first, b = last + 1;  // valid states around the run
    for (std::size_t r = 0; r < robots.size(); ++r)
      for (std::size_t t = copied_to; t <= a; ++t) repaired[r].push(paths[r].at(t));
    CoupledQuery q;
    q.robots = robots;
    q.starts = stateAt(paths, a);
    q.goals = stateAt(paths, b);
    q.region = region;
    CoupledSettings cs;
    cs.time_limit_s = time_per_run_s;
    cs.within = deadline;
    cs.polish = true;
    if (deadline.expired()) return {std::nullopt, true, "no time left to repair"};
    auto fix = solveCoupled(world, q, cs, splitSeed(seed, a));
    if (!fix) return {std::nullopt, false, "repair failed"};
    for (std::size_t r = 0; r < robots.size(); ++r) repaired[r].append(fix->paths[r], 1);
    copied_to = b + 1;
  }
  for (std::size_t r = 0; r < robots.size(); ++r)
    for (std::size_t t = copied_to; t < paths[r].size(); ++t) repaired[r].push(paths[r].at(t));
  return {std::move(repaired), false, ""};
}

// A solution whose paths all have the same length, start at the starts and
// end at the goals, respect the resolution, and are free of obstacles,
// self-collision and contact between the query's robots at every step and
// midpoint; std::nullopt when none was found within the time limit.
// Deterministic for a given seed when the time limit is not what stops it.
std::optional<LocalSolution> solveCoupled(const CollisionWorld& world, const CoupledQuery& query,
                                          const CoupledSettings& settings, std::uint64_t seed) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  // The limit covers the checks and the setup before OMPL's search too: on
  // thousands of robots they are not negligible.
  const Deadline deadline = settings.within.capped(settings.time_limit_s);
  CompositeChecker checker(world, query.robots, deadline);
  if (!checker.stateValid(query.starts) || !checker.stateValid(query.goals)) return std::nullopt;
  std::vector<std::vector<std::vector<double>>> waypoints;
  // The straight composite motion is the common answer for small, local
  // subproblems; try it before building any tree.
  if (checker.motionValid(query.starts, query.goals)) {
    waypoints = {query.starts, query.goals};
    return timeStampComposite(query.robots, waypoints);
  }
  if (deadline.expired()) return std::nullopt;

  OmplComposite composite(checker, compositeBounds(world, query.robots, query.region, {query.starts, query.goals}));
  composite.setSeed(seed);
  // The planner allocates its sampler in solve(), on this thread.
  SeededPlanningStream stream(kSamplerStream);
  const ob::SpaceInformationPtr& si = composite.spaceInformation();
  ob::ScopedState<> start(composite.space()), goal(composite.space());
  composite.fromComposite(query.starts, start.get());
  composite.fromComposite(query.goals, goal.get());
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(start, goal);
  auto planner = std::make_shared<og::RRTConnect>(si);
  planner->setProblemDefinition(pdef);
  planner->setup();
  // The time limit, or sooner on a stop request (Deadline::stoppedBy).
  const ob::PlannerTerminationCondition ptc([&deadline] { return deadline.expired(); });
  ob::PlannerStatus status = planner->solve(ptc);
  if (status != ob::PlannerStatus::EXACT_SOLUTION) return std::nullopt;

  auto* path = pdef->getSolutionPath()->as<og::PathGeometric>();
  waypoints.assign(path->getStateCount(), {});
  for (std::size_t i = 0; i < waypoints.size(); ++i) composite.toComposite(path->getState(i), waypoints[i]);
  // OMPL hands back the goal with its wrapped heading; restore the exact
  // query endpoints (equal modulo 2 pi, so motions are unchanged).
  waypoints.front() = query.starts;
  waypoints.back() = query.goals;
  if (settings.simplify) {
    std::mt19937_64 rng(splitSeed(seed, 0x5c07));
    shortcutComposite(checker, waypoints, kShortcutIterations, rng, deadline);
    if (settings.polish) polishComposite(checker, waypoints, rng, deadline);
  }
  return timeStampComposite(query.robots, waypoints);
}

SolverOutcome CoupledSubproblemSolver::solve(SolverContext& ctx) {
  const Subproblem& sub = ctx.sub;
  if (ctx.deadline.expired()) return {std::nullopt, name(), -1};
  const std::size_t window = sub.t_end - sub.t_start + 1;
  auto padded = [&](LocalSolution sol, const char* detail) {
    const std::size_t len = std::max(sol.length(), window);
    for (auto& p : sol.paths)
      while (p.size() < len) p.push(p.back());
    return SolverOutcome{std::move(sol), name(), -1, 0.0, detail};
  };
  // Robots parked at their final goals are held as obstacles first: moved
  // aside and back, one costs every step since it arrived.
  if (settings_.parked_held) {
    if (auto held = solveAroundParked(ctx)) return padded(std::move(*held), "around the parked robots");
    if (ctx.deadline.expired()) return {std::nullopt, name(), -1};
  }
  CoupledQuery q;
  for (int r : sub.robots) q.robots.push_back(ctx.models[static_cast<std::size_t>(r)]);
  q.starts = sub.starts;
  q.goals = sub.goals;
  q.region = sub.region;
  CoupledSettings cs;
  cs.time_limit_s = settings_.time_budget_s * ctx.budget_scale;
  cs.within = ctx.deadline;
  cs.polish = true;
  auto sol = solveCoupled(ctx.world, q, cs, ctx.seed);
  if (!sol) return {std::nullopt, name(), -1};
  return padded(std::move(*sol), "");
}

std::optional<LocalSolution> CoupledSubproblemSolver::solveAroundParked(const SolverContext& ctx) const {
  const Subproblem& sub = ctx.sub;
  std::vector<std::size_t> moving;
  std::vector<geo::Body> held;
  std::vector<geo::Body> bodies;
  for (std::size_t i = 0; i < sub.robots.size(); ++i) {
    const auto r = static_cast<std::size_t>(sub.robots[i]);
    const RobotModel& m = *ctx.models[r];
    if (m.isMobile() && ctx.paths[r].size() <= sub.t_start + 1) {
      m.bodies(sub.starts[i].data(), bodies);
      held.insert(held.end(), bodies.begin(), bodies.end());
    } else {
      moving.push_back(i);
    }
  }
  if (held.empty() || moving.empty()) return std::nullopt;
  const std::optional<Scenario> scene = sceneWith(ctx.world, held);
  if (!scene) return std::nullopt;
  const CollisionWorld world(*scene);
  CoupledQuery q;
  for (std::size_t i : moving) {
    q.robots.push_back(ctx.models[static_cast<std::size_t>(sub.robots[i])]);
    q.starts.push_back(sub.starts[i]);
    q.goals.push_back(sub.goals[i]);
    q.region.push_back(sub.region[i]);
  }
  CoupledSettings cs;
  cs.time_limit_s = settings_.time_budget_s * ctx.budget_scale * kParkedHeldShare;
  cs.within = ctx.deadline;
  cs.polish = true;
  auto part = solveCoupled(world, q, cs, splitSeed(ctx.seed, 0x9a2c));
  if (!part) return std::nullopt;
  const std::size_t len = part->length();
  LocalSolution sol;
  for (std::size_t i = 0; i < sub.robots.size(); ++i) {
    const auto at = std::find(moving.begin(), moving.end(), i);
    if (at != moving.end()) {
      sol.paths.push_back(std::move(part->paths[static_cast<std::size_t>(at - moving.begin())]));
      continue;
    }
    Path still(static_cast<int>(sub.starts[i].size()));
    for (std::size_t t = 0; t < len; ++t) still.push(sub.starts[i].data());
    sol.paths.push_back(std::move(still));
  }
  return sol;
}

}  // namespace earc
