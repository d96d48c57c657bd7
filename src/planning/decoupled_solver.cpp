// Prioritized planning in space-time over roadmaps (ARC's first solver).
#include <algorithm>
#include <numeric>
#include <queue>
#include <unordered_map>

#include "earc/planning/conflict.hpp"
#include "earc/planning/coupled_solver.hpp"
#include "earc/planning/solver.hpp"
#include "earc/util/random.hpp"

namespace earc {

namespace {

// Checks one robot configuration against moving obstacles at a local instant.
class MotionGuard {
 public:
  MotionGuard(const RobotModel& model, const std::vector<MovingObstacle>& obstacles)
      : model_(model), obstacles_(obstacles) {
    for (const auto& o : obstacles_) scratch_.emplace_back(static_cast<std::size_t>(o.model->dim()));
  }

  bool free(const double* q, std::size_t instant) {
    const geo::Vec2 c = model_.boundingCenter(q);
    const double r = model_.boundingRadius();
    for (std::size_t i = 0; i < obstacles_.size(); ++i) {
      const MovingObstacle& o = obstacles_[i];
      double* oq = scratch_[i].data();
      stateAtInstant(*o.model, *o.path, 2 * o.offset + instant, oq);
      const geo::Vec2 oc = o.model->boundingCenter(oq);
      const double reach = r + o.model->boundingRadius();
      const geo::Vec2 d = c - oc;
      if (d.x * d.x + d.y * d.y > reach * reach) continue;
      if (robotsTouch(model_, q, *o.model, oq)) return false;
    }
    return true;
  }

 private:
  const RobotModel& model_;
  const std::vector<MovingObstacle>& obstacles_;
  std::vector<std::vector<double>> scratch_;
};

std::uint64_t nodeKey(int v, std::size_t tau) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(v)) << 32) | static_cast<std::uint32_t>(tau);
}

}  // namespace

std::optional<Path> spaceTimeSearch(QueryGraph& graph, int start, int goal,
                                    const std::vector<MovingObstacle>& obstacles, std::size_t horizon,
                                    std::size_t hold_until, const Deadline& deadline, std::size_t max_expansions) {
  const RobotModel& model = graph.model();
  const int dim = model.dim();
  MotionGuard guard(model, obstacles);
  if (!guard.free(graph.config(start), 0)) return std::nullopt;

  std::vector<double> h(static_cast<std::size_t>(graph.size()), -1.0);
  auto heuristic = [&](int v) {
    double& x = h[static_cast<std::size_t>(v)];
    if (x < 0) x = model.distance(graph.config(v), graph.config(goal));
    return x;
  };
  auto holds = [&](int v, std::size_t tau) {
    for (std::size_t k = 2 * tau; k <= 2 * std::max(hold_until, tau); ++k)
      if (!guard.free(graph.config(v), k)) return false;
    return true;
  };

  struct Item {
    double f;
    std::size_t tau;
    int v;
    bool operator>(const Item& o) const { return f != o.f ? f > o.f : tau < o.tau; }  // deeper first on ties
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  std::unordered_map<std::uint64_t, std::uint64_t> parent;  // (v, tau) -> predecessor
  std::unordered_map<std::uint64_t, char> closed;
  const std::uint64_t root = nodeKey(start, 0);
  parent.emplace(root, root);
  open.push({heuristic(start), 0, start});
  std::vector<double> q(static_cast<std::size_t>(dim));
  std::size_t expansions = 0;
  std::optional<std::uint64_t> found;

  while (!open.empty()) {
    Item it = open.top();
    open.pop();
    const std::uint64_t key = nodeKey(it.v, it.tau);
    if (!closed.emplace(key, 1).second) continue;
    if (it.v == goal && holds(it.v, it.tau)) {
      found = key;
      break;
    }
    if (++expansions > max_expansions) break;
    if ((expansions & 255) == 0 && deadline.expired()) break;
    if (it.tau >= horizon) continue;
    auto push = [&](int u, std::size_t tau) {
      const std::uint64_t k = nodeKey(u, tau);
      if (parent.count(k)) return;
      parent.emplace(k, key);
      open.push({static_cast<double>(tau) + heuristic(u), tau, u});
    };
    // Wait one step.
    const double* here = graph.config(it.v);
    if (guard.free(here, 2 * it.tau + 1) && guard.free(here, 2 * it.tau + 2)) push(it.v, it.tau + 1);
    // Move along an edge.
    graph.forEachEdge(it.v, [&](int u, int steps, int edge) {
      const std::size_t arrive = it.tau + static_cast<std::size_t>(steps);
      if (arrive > horizon || parent.count(nodeKey(u, arrive))) return;
      if (!graph.edgeValid(edge)) return;
      const double* there = graph.config(u);
      for (int k = 1; k <= 2 * steps; ++k) {
        model.interpolate(here, there, static_cast<double>(k) / (2 * steps), q.data());
        if (!guard.free(q.data(), 2 * it.tau + static_cast<std::size_t>(k))) return;
      }
      push(u, arrive);
    });
  }
  if (!found) return std::nullopt;

  std::vector<std::pair<int, std::size_t>> nodes;
  for (std::uint64_t k = *found;; k = parent.at(k)) {
    nodes.emplace_back(static_cast<int>(k >> 32), static_cast<std::size_t>(k & 0xffffffffu));
    if (k == root) break;
  }
  std::reverse(nodes.begin(), nodes.end());
  Path path(dim);
  path.push(graph.config(nodes.front().first));
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    const double* a = graph.config(nodes[i - 1].first);
    const double* b = graph.config(nodes[i].first);
    const std::size_t steps = nodes[i].second - nodes[i - 1].second;
    for (std::size_t k = 1; k <= steps; ++k) {
      if (k == steps) {
        path.push(b);
      } else {
        model.interpolate(a, b, static_cast<double>(k) / static_cast<double>(steps), q.data());
        path.push(q.data());
      }
    }
  }
  return path;
}

std::vector<MovingObstacle> nearbyRobots(const SolverContext& ctx, std::size_t span) {
  std::vector<MovingObstacle> out;
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

SolverOutcome DecoupledSolver::solve(SolverContext& ctx) {
  const Subproblem& sub = ctx.sub;
  const std::size_t n = sub.robots.size();
  const std::size_t window = sub.t_end - sub.t_start;  // steps in the replaced span
  const std::size_t horizon = 4 * window + 100;
  const Deadline deadline = ctx.deadline.capped(settings_.time_budget_s);
  std::vector<MovingObstacle> others;
  if (settings_.avoid_others) others = nearbyRobots(ctx, horizon);

  std::vector<std::vector<std::size_t>> orders;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  orders.push_back(order);
  if (n > 1) orders.emplace_back(order.rbegin(), order.rend());
  std::mt19937_64 rng(splitSeed(ctx.seed, 0xdec0));
  while (static_cast<int>(orders.size()) < settings_.max_orders && n > 2) {
    std::shuffle(order.begin(), order.end(), rng);
    orders.push_back(order);
  }

  for (const auto& ord : orders) {
    if (deadline.expired()) break;
    std::vector<Path> local(n);
    std::vector<MovingObstacle> obstacles = others;
    std::size_t hold = window;
    bool ok = true;
    for (std::size_t i : ord) {
      const int robot = sub.robots[i];
      QueryGraph graph(ctx.roadmaps.forRobot(robot), &sub.region[i]);
      int s = graph.addVertex(sub.starts[i].data(), settings_.connect_neighbors);
      int g = graph.addVertex(sub.goals[i].data(), settings_.connect_neighbors);
      auto p = spaceTimeSearch(graph, s, g, obstacles, horizon, hold, deadline, settings_.max_expansions);
      if (!p) {
        ok = false;
        break;
      }
      local[i] = std::move(*p);
      hold = std::max(hold, local[i].size() - 1);
      obstacles.push_back({ctx.models[static_cast<std::size_t>(robot)], &local[i], 0, robot});
    }
    if (!ok) continue;
    LocalSolution sol;
    sol.paths = std::move(local);
    std::size_t len = window + 1;
    for (const auto& p : sol.paths) len = std::max(len, p.size());
    for (auto& p : sol.paths)
      while (p.size() < len) p.push(p.back());
    return {std::move(sol), name(), -1};
  }
  return {std::nullopt, name(), -1};
}

SolverOutcome CoupledSubproblemSolver::solve(SolverContext& ctx) {
  const Subproblem& sub = ctx.sub;
  CoupledQuery q;
  for (int r : sub.robots) q.robots.push_back(ctx.models[static_cast<std::size_t>(r)]);
  q.starts = sub.starts;
  q.goals = sub.goals;
  q.region = sub.region;
  CoupledSettings cs;
  cs.time_limit_s = std::min(settings_.time_budget_s, ctx.deadline.remaining());
  if (cs.time_limit_s <= 0) return {std::nullopt, name(), -1};
  auto sol = solveCoupled(ctx.world, q, cs, ctx.seed);
  if (!sol) return {std::nullopt, name(), -1};
  const std::size_t len = std::max(sol->length(), sub.t_end - sub.t_start + 1);
  for (auto& p : sol->paths)
    while (p.size() < len) p.push(p.back());
  return {std::move(sol), name(), -1};
}

}  // namespace earc
