// Prioritized planning in space-time over roadmaps (ARC's first solver):
// the robots around a subproblem, priority orders, and the solver itself.
#include <algorithm>
#include <numeric>
#include <tuple>

#include "earc/planning/solver.hpp"
#include "earc/util/random.hpp"

namespace earc {

std::vector<MovingObstacle> nearbyRobots(const SolverContext& ctx, std::size_t span) {
  std::vector<MovingObstacle> out;
  if (ctx.ignore_others) return out;
  const Subproblem& sub = ctx.sub;
  std::vector<geo::Body> bodies;
  for (std::size_t r = 0; r < ctx.models.size(); ++r) {
    if (std::find(sub.robots.begin(), sub.robots.end(), static_cast<int>(r)) != sub.robots.end()) continue;
    const Path& p = ctx.paths[r];
    if (p.empty()) continue;
    const RobotModel& m = *ctx.models[r];
    geo::Aabb swept;
    const std::size_t last = std::min(p.size() - 1, sub.t_start + span);
    const std::size_t first = std::min(sub.t_start, p.size() - 1);
    for (std::size_t t = first; t <= last; ++t) {
      geo::Vec2 c = m.boundingCenter(p.at(t));
      swept.expand({c, c});
    }
    if (swept.inflated(m.boundingRadius()).overlaps(sub.workspace_region))
      out.push_back({&m, &p, sub.t_start, static_cast<int>(r)});
  }
  return out;
}

std::vector<std::size_t> nextPriorityOrder(const std::vector<std::vector<std::size_t>>& tried, std::size_t failed,
                                           std::mt19937_64& rng) {
  if (tried.empty()) return {};
  auto untried = [&](const std::vector<std::size_t>& o) { return std::find(tried.begin(), tried.end(), o) == tried.end(); };
  // The last order with the robot that failed moved to its front.
  std::vector<std::size_t> next = tried.back();
  const auto at = std::find(next.begin(), next.end(), failed);
  if (at != next.end()) std::rotate(next.begin(), at, at + 1);
  if (untried(next)) return next;
  // Else one not tried yet, drawn at random: by shuffling where there
  // are many orders (6 robots have 720), among all that are left where
  // there are few or shuffling keeps meeting tried ones. Past 8 robots
  // (40,320 orders) that is never needed: max_orders is at most 10,000.
  const std::size_t n = next.size();
  if (n > 5) {
    for (int k = 0; k < 64; ++k) {
      std::shuffle(next.begin(), next.end(), rng);
      if (untried(next)) return next;
    }
    if (n > 8) return {};
  }
  std::vector<std::vector<std::size_t>> left;
  std::sort(next.begin(), next.end());
  do {
    if (untried(next)) left.push_back(next);
  } while (std::next_permutation(next.begin(), next.end()));
  if (left.empty()) return {};
  return left[std::uniform_int_distribution<std::size_t>(0, left.size() - 1)(rng)];
}

SolverOutcome DecoupledSolver::solve(SolverContext& ctx) {
  const Subproblem& sub = ctx.sub;
  const std::size_t n = sub.robots.size();
  const std::size_t window = sub.t_end - sub.t_start;  // steps in the replaced span
  // Roadmaps are built when a robot first needs one (see individualPath):
  // build this subproblem's before the search's budget starts, so that
  // building one does not take the search's time.
  for (int robot : sub.robots) ctx.roadmaps.forRobot(robot);
  const Deadline deadline = ctx.deadline.capped(settings_.time_budget_s * ctx.budget_scale);
  // Past ARC's last expansion level the hierarchy raises budget_scale
  // to retry the same subproblem: every limit grows with it, or the
  // retries repeat the same failed searches (a 4-robot corridor swap that
  // needs a fifth priority order never got it).
  const double scale = std::max(1.0, ctx.budget_scale);
  // The horizon grows with it too, up to the long horizon (not beyond:
  // each instant of it is tabulated for every robot around).
  const double w = static_cast<double>(window);
  const double base_horizon = settings_.horizon_windows * w + static_cast<double>(settings_.horizon_steps);
  const double long_horizon = DecoupledSettings::kLongHorizonWindows * w +
                              static_cast<double>(DecoupledSettings::kLongHorizonSteps);
  const std::size_t horizon =
      static_cast<std::size_t>(std::max(base_horizon, std::min(base_horizon * scale, long_horizon)));
  std::size_t max_expansions = static_cast<std::size_t>(std::min(1e9, static_cast<double>(settings_.max_expansions) * scale));
  const int max_orders = static_cast<int>(std::min(1e4, settings_.max_orders * scale));
  if (settings_.expansions_per_horizon_step > 0)
    max_expansions = std::min(max_expansions, static_cast<std::size_t>(static_cast<double>(
                                                  settings_.expansions_per_horizon_step * horizon) * ctx.budget_scale));
  std::vector<MovingObstacle> others;
  if (settings_.avoid_others) others = nearbyRobots(ctx, horizon);

  // The robots as listed first; after a failure, the next order comes
  // from nextPriorityOrder.
  std::vector<std::vector<std::size_t>> tried_orders;
  std::vector<std::size_t> ord(n);
  std::iota(ord.begin(), ord.end(), 0);
  // Robots already standing at their final goals go first: one moved
  // aside and back costs every step since it arrived, where the robot
  // that meets it can often pass around it (a parked robot planned second
  // was pushed off its goal for hundreds of steps).
  std::vector<char> parked(n, 0);
  for (std::size_t i = 0; i < n; ++i) parked[i] = ctx.paths[static_cast<std::size_t>(sub.robots[i])].size() <= sub.t_start + 1;
  std::stable_partition(ord.begin(), ord.end(), [&](std::size_t i) { return parked[i] != 0; });
  std::mt19937_64 rng(splitSeed(ctx.seed, 0xdec0));

  // A robot planned first meets only the robots outside the group. If it
  // runs out of ways then (not out of expansions), it would find none in
  // any order, behind more robots and holding its goal no sooner: the
  // attempt ends there instead of trying the other orders.
  // The last failure (also for the trace): robot, its place in the
  // order, how its search ended.
  int last_robot = -1;
  std::size_t last_place = 0;
  SearchEnd last_end = SearchEnd::Found;
  auto hopeless = [&] { return last_end == SearchEnd::NoWay && last_place == 0; };
  // One order's attempt: each robot's search in turn, against the robots
  // outside and those planned before it. `whole`: the moving robots over
  // their whole roadmaps, among every robot outside the group.
  std::vector<MovingObstacle> everyone;
  bool whole_tried = false;
  auto attempt = [&](const std::vector<std::size_t>& order, bool whole, std::vector<Path>& local) {
    const std::vector<MovingObstacle>& around = whole ? everyone : others;
    std::vector<MovingObstacle> obstacles = around;
    std::size_t hold = window;
    for (std::size_t i : order) {
      const int robot = sub.robots[i];
      QueryGraph graph(ctx.roadmaps.forRobot(robot), *ctx.models[static_cast<std::size_t>(robot)],
                       whole && !parked[i] ? nullptr : &sub.region[i]);
      int s = graph.addVertex(sub.starts[i].data(), settings_.connect_neighbors);
      int g = graph.addVertex(sub.goals[i].data(), settings_.connect_neighbors);
      SearchEnd end = SearchEnd::Found;
      auto p = spaceTimeSearch(graph, s, g, obstacles, horizon, hold, deadline, max_expansions,
                               settings_.graph_heuristic, &end);
      if (!p) {
        last_robot = robot;
        last_place = obstacles.size() - around.size();
        last_end = end;
        return false;
      }
      local[i] = std::move(*p);
      hold = std::max(hold, local[i].size() - 1);
      obstacles.push_back({ctx.models[static_cast<std::size_t>(robot)], &local[i], 0, robot});
    }
    return true;
  };
  // Whether `order` plans a robot that is not parked before one that is.
  auto movesParked = [&](const std::vector<std::size_t>& order) {
    bool moving_before = false;
    for (std::size_t i : order) {
      if (parked[i] && moving_before) return true;
      moving_before = moving_before || !parked[i];
    }
    return false;
  };
  auto answer = [&](std::vector<Path> local) {
    LocalSolution sol;
    sol.paths = std::move(local);
    std::size_t len = window + 1;
    for (const auto& p : sol.paths) len = std::max(len, p.size());
    for (auto& p : sol.paths)
      while (p.size() < len) p.push(p.back());
    return SolverOutcome{std::move(sol), name(), -1};
  };
  while (static_cast<int>(tried_orders.size()) < max_orders && !ord.empty()) {
    if (deadline.expired() || hopeless()) break;
    // Before an order that may push a parked robot off its goal (which
    // costs every step since it arrived), the others once more with the
    // parked robots first, around them over the whole workspace.
    if (!whole_tried && settings_.parked_detour && movesParked(ord)) {
      whole_tried = true;
      if (!ctx.ignore_others)
        for (std::size_t r = 0; r < ctx.models.size(); ++r)
          if (!std::binary_search(sub.robots.begin(), sub.robots.end(), static_cast<int>(r)) && !ctx.paths[r].empty())
            everyone.push_back({ctx.models[r], &ctx.paths[r], sub.t_start, static_cast<int>(r)});
      std::vector<Path> local(n);
      const auto before = std::tuple(last_robot, last_place, last_end);  // what the orders' failures said
      if (attempt(tried_orders.empty() ? ord : tried_orders.front(), true, local)) {
        SolverOutcome out = answer(std::move(local));
        out.detail = "around the parked robots";
        return out;
      }
      std::tie(last_robot, last_place, last_end) = before;
      if (deadline.expired()) break;
    }
    tried_orders.push_back(ord);
    std::vector<Path> local(n);
    if (!attempt(ord, false, local)) {
      ord = nextPriorityOrder(tried_orders, ord[last_place], rng);  // the robot that failed
      continue;
    }
    return answer(std::move(local));
  }
  SolverOutcome failed{std::nullopt, name(), -1};
  if (hopeless())
    failed.detail = "robot " + std::to_string(last_robot) + " has no way past the robots outside the group, in any order";
  else if (last_robot >= 0)
    failed.detail = std::to_string(tried_orders.size()) +
                    (tried_orders.size() == 1 ? " priority order" : " priority orders") +
                    " failed; in the last, robot " +
                    std::to_string(last_robot) + " (" + std::to_string(last_place + 1) + " of " +
                    std::to_string(n) + "): " + searchEndName(last_end);
  return failed;
}

}  // namespace earc
