// The space-time search (spaceTimeSearch): A* over (roadmap vertex, step)
// among moving obstacles, and the check of a path against them.
#include <algorithm>
#include <limits>
#include <queue>
#include <unordered_map>

#include "earc/planning/solver.hpp"
#include "motion_guard.hpp"

namespace earc {

namespace {

using spacetime::MotionGuard;
using spacetime::spanOf;

// Units of work (Deadline::withWorkBudgets) of one expansion of the
// space-time search, beside its collision checks: about its time.
constexpr std::size_t kWorkPerExpansion = 4;

// Two 32-bit values in one 64-bit key, the first in the high half.
std::uint64_t packPair(std::uint32_t hi, std::uint32_t lo) { return (static_cast<std::uint64_t>(hi) << 32) | lo; }

std::uint64_t nodeKey(int v, std::size_t tau) {
  return packPair(static_cast<std::uint32_t>(v), static_cast<std::uint32_t>(tau));
}

std::uint64_t motionKey(int from, int to) {
  return packPair(static_cast<std::uint32_t>(from), static_cast<std::uint32_t>(to));
}

// Fills h with each vertex's steps to `goal` over every edge not known
// invalid (unchecked ones count as valid): no more than the robot needs, and
// consistent; infinity where the goal is not reached. False when the
// deadline expired first.
bool goalDistances(QueryGraph& graph, int goal, DeadlinePoll& poll, std::vector<double>& h) {
  const double unreached = std::numeric_limits<double>::infinity();
  std::fill(h.begin(), h.end(), unreached);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> frontier;
  h[static_cast<std::size_t>(goal)] = 0;
  frontier.push({0.0, goal});
  // Polled as it works: a whole map's roadmap can have 80,000 vertices.
  while (!frontier.empty()) {
    if (poll.expired(kWorkPerGraphPop)) return false;
    const auto [d, v] = frontier.top();
    frontier.pop();
    if (d > h[static_cast<std::size_t>(v)]) continue;
    graph.forEachEdge(v, [&](int u, int steps, int edge) {
      if (graph.knownInvalid(edge) || d + steps >= h[static_cast<std::size_t>(u)]) return;
      h[static_cast<std::size_t>(u)] = d + steps;
      frontier.push({d + steps, u});
    });
  }
  return true;
}

// The earliest arrival from which the robot can wait at `goal` through
// hold_until; hold_until + 1 when there is none.
std::size_t earliestHold(MotionGuard& guard, const double* goal, std::size_t hold_until) {
  for (std::size_t k = 2 * hold_until + 1; k-- > 0;)
    if (!guard.free(goal, k)) return k / 2 + 1;
  return 0;
}

// Where the robot's bounding centre can be during the search: its region
// and the straight way from start to goal; everywhere without a region.
geo::Aabb searchArea(QueryGraph& graph, const RobotModel& model, int start, int goal) {
  geo::Aabb where{{-1e300, -1e300}, {1e300, 1e300}};
  if (const ConfigBox* region = graph.region()) {
    where = spanOf(model.boundingCenter(region->lo.data()), model.boundingCenter(region->hi.data()));
    where.expand(spanOf(model.boundingCenter(graph.config(start)), model.boundingCenter(graph.config(goal))));
  }
  return where;
}

// The path from the search's root to node `found`, each edge's motion
// interpolated step by step.
Path tracePath(QueryGraph& graph, const std::unordered_map<std::uint64_t, std::uint64_t>& parent, std::uint64_t found,
               std::uint64_t root) {
  const RobotModel& model = graph.model();
  std::vector<std::pair<int, std::size_t>> nodes;
  for (std::uint64_t k = found;; k = parent.at(k)) {
    nodes.emplace_back(static_cast<int>(k >> 32), static_cast<std::size_t>(k & 0xffffffffu));
    if (k == root) break;
  }
  std::reverse(nodes.begin(), nodes.end());
  std::vector<double> q(static_cast<std::size_t>(model.dim()));
  Path path(model.dim());
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

}  // namespace

const char* searchEndName(SearchEnd end) {
  switch (end) {
    case SearchEnd::Found: return "found";
    case SearchEnd::NoWay: return "no way";
    case SearchEnd::Capped: return "expansion cap";
    case SearchEnd::OutOfTime: return "out of time";
  }
  return "?";
}

// The heuristic is the straight-line distance to the goal in steps, or with
// graph_heuristic the steps of the shortest way over the graph's edges not
// known to be invalid (goalDistances): as admissible, and far better
// informed on a maze-like map, where the straight line runs through walls.
std::optional<Path> spaceTimeSearch(QueryGraph& graph, int start, int goal,
                                    const std::vector<MovingObstacle>& obstacles, std::size_t horizon,
                                    std::size_t hold_until, const Deadline& deadline, std::size_t max_expansions,
                                    bool graph_heuristic, SearchEnd* end) {
  const RobotModel& model = graph.model();
  DeadlinePoll poll(deadline, kWorkPerClockRead);
  MotionGuard guard(model, obstacles, 2 * std::max(horizon, hold_until) + 2, &poll);
  bool capped = false;  // stopped at max_expansions
  auto fail = [&]() -> std::optional<Path> {
    if (end)
      *end = capped ? SearchEnd::Capped
             : poll.seenExpired() || graph.roadmap().poll().seenExpired() || deadline.expired() ? SearchEnd::OutOfTime
                                                                                                : SearchEnd::NoWay;
    return std::nullopt;
  };
  if (!guard.free(graph.config(start), 0)) return fail();
  // Unreachable in the region even with time ignored: say so now rather than
  // after enumerating every (vertex, time) pair up to the horizon.
  if (!shortestPath(graph, start, goal, deadline)) return fail();

  std::vector<double> h(static_cast<std::size_t>(graph.size()), -1.0);
  if (graph_heuristic && !goalDistances(graph, goal, poll, h)) return fail();
  auto heuristic = [&](int v) {
    double& x = h[static_cast<std::size_t>(v)];
    if (x < 0) x = model.distance(graph.config(v), graph.config(goal));
    return x;
  };
  // When the goal is taken at hold_until itself there is no arrival to
  // hold it, and searching the whole space-time graph to find that out is
  // the most expensive way a subproblem fails.
  const std::size_t earliest_hold = earliestHold(guard, graph.config(goal), hold_until);
  if (earliest_hold > hold_until) return fail();
  // Arriving later than hold_until needs only the arrival instant free.
  auto holds = [&](int v, std::size_t tau) {
    return tau >= earliest_hold && (tau <= hold_until || guard.free(graph.config(v), 2 * tau));
  };
  auto priority = [&](int v, std::size_t tau) {
    return std::max(static_cast<double>(tau) + heuristic(v), static_cast<double>(earliest_hold));
  };
  // From step `still` on, nothing within reach of the robot's region
  // moves: being at a vertex earlier is as good as being there later (it
  // can wait), so a vertex reached again no sooner than before is not
  // searched again. Waits at the goal are kept: holding it may need a
  // later arrival.
  const std::size_t still = guard.stillFrom(searchArea(graph, model, start, goal));
  // Steps pushed reach the horizon at most: a world still only later
  // needs no table.
  std::vector<std::size_t> still_since(still <= horizon ? static_cast<std::size_t>(graph.size()) : 0,
                                       std::numeric_limits<std::size_t>::max());

  struct Item {
    double f;
    std::size_t tau;
    int v;
    bool operator>(const Item& o) const { return f != o.f ? f > o.f : tau < o.tau; }  // deeper first on ties
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  // (v, tau) -> predecessor. A node enters the queue only with its first
  // parent, so it leaves it once: no closed set is needed.
  std::unordered_map<std::uint64_t, std::uint64_t> parent;
  const std::uint64_t root = nodeKey(start, 0);
  parent.emplace(root, root);
  open.push({priority(start, 0), 0, start});
  std::size_t expansions = 0;
  std::optional<std::uint64_t> found;

  while (!open.empty()) {
    Item it = open.top();
    open.pop();
    const std::uint64_t key = nodeKey(it.v, it.tau);
    if (it.v == goal && holds(it.v, it.tau)) {
      found = key;
      break;
    }
    // The heuristic never overestimates: once the least f in the queue
    // is past the horizon, no arrival by the horizon is left to find.
    // (Searches that fail used to go on to the horizon, the expansion cap
    // or the budget; a half step of margin covers the metric's rounding
    // slack in step counts.)
    if (it.f > static_cast<double>(horizon) + 0.5) break;
    if (++expansions > max_expansions) {
      capped = true;
      break;
    }
    // The queue and the table of states reached count as work (see
    // MotionGuard). The poll is also read where the work is (MotionGuard
    // and Roadmap::edgeValid): an expansion on arms of thousands of links
    // can take a second.
    if (poll.expired(kWorkPerExpansion) || graph.roadmap().poll().seenExpired()) break;
    if (it.tau >= horizon) continue;
    auto push = [&](int u, std::size_t tau) {
      const double f = priority(u, tau);
      if (f == std::numeric_limits<double>::infinity()) return;  // no way on to the goal
      if (tau >= still && u != goal) {
        std::size_t& since = still_since[static_cast<std::size_t>(u)];
        if (since <= tau) return;
        since = tau;
      }
      if (parent.try_emplace(nodeKey(u, tau), key).second) open.push({f, tau, u});
    };
    // Wait one step.
    const double* here = graph.config(it.v);
    if (guard.free(here, 2 * it.tau + 1) && guard.free(here, 2 * it.tau + 2)) push(it.v, it.tau + 1);
    // Move along an edge.
    graph.forEachEdge(it.v, [&](int u, int steps, int edge) {
      const std::size_t arrive = it.tau + static_cast<std::size_t>(steps);
      if (arrive > horizon || parent.count(nodeKey(u, arrive))) return;
      if (!graph.edgeValid(edge)) return;
      if (steps > 0 && !guard.motionFree(here, graph.config(u), steps, it.tau, motionKey(it.v, u))) return;
      push(u, arrive);
    });
  }
  if (!found) return fail();
  if (end) *end = SearchEnd::Found;
  return tracePath(graph, parent, *found, root);
}

bool clearOfMoving(const RobotModel& model, const Path& local, const std::vector<MovingObstacle>& obstacles) {
  if (local.empty() || obstacles.empty()) return true;
  const std::size_t last_step = local.size() - 1;
  MotionGuard guard(model, obstacles, 2 * last_step + 2);
  if (!guard.free(local.at(0), 0)) return false;
  for (std::size_t t = 0; t < last_step; ++t)
    if (!guard.motionFree(local.at(t), local.at(t + 1), 1, t)) return false;
  return true;
}

}  // namespace earc
