// The roadmap's lazy shortest path against an eager search that checks
// every edge it meets: the same lengths, and only valid edges on the way.
#include <doctest/doctest.h>

#include <limits>
#include <queue>
#include <random>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/roadmap.hpp"
#include "earc/scene/robot_model.hpp"

namespace earc {
namespace {

// Steps of the shortest valid way from `from` to `to`, every edge checked
// before it is used (Dijkstra); -1 when there is none.
long long eagerSteps(QueryGraph& graph, int from, int to) {
  std::vector<long long> dist(static_cast<std::size_t>(graph.size()), std::numeric_limits<long long>::max());
  using Item = std::pair<long long, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  dist[static_cast<std::size_t>(from)] = 0;
  open.push({0, from});
  while (!open.empty()) {
    const auto [d, v] = open.top();
    open.pop();
    if (d > dist[static_cast<std::size_t>(v)]) continue;
    if (v == to) return d;
    std::vector<std::pair<int, int>> out;  // (vertex, steps) of valid edges
    std::vector<int> keys;
    graph.forEachEdge(v, [&](int u, int steps, int key) {
      out.push_back({u, steps});
      keys.push_back(key);
    });
    for (std::size_t k = 0; k < out.size(); ++k) {
      if (!graph.edgeValid(keys[k])) continue;
      const long long c = d + out[k].second;
      if (c < dist[static_cast<std::size_t>(out[k].first)]) {
        dist[static_cast<std::size_t>(out[k].first)] = c;
        open.push({c, out[k].first});
      }
    }
  }
  return -1;
}

// The steps of a vertex sequence's edges, each of which must be valid.
long long pathSteps(QueryGraph& graph, const std::vector<int>& path, bool& all_valid) {
  long long total = 0;
  all_valid = true;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    int best_steps = -1, best_key = 0;
    graph.forEachEdge(path[k], [&](int u, int steps, int key) {
      if (u == path[k + 1] && (best_steps < 0 || steps < best_steps)) {
        best_steps = steps;
        best_key = key;
      }
    });
    if (best_steps < 0 || !graph.edgeValid(best_key)) all_valid = false;
    total += best_steps;
  }
  return total;
}

TEST_CASE("The lazy shortest path is as short as an eager search's and uses valid edges only") {
  Scenario s;
  s.name = "walls";
  s.workspace = {{0, 0}, {12, 12}};
  // Walls with gaps: many roadmap edges cross them, so that the lazy
  // search meets invalid edges on its first candidates.
  for (double y : {3.0, 6.0, 9.0}) {
    s.obstacles.push_back(Obstacle::makeBox({4.0 + y / 3.0, y}, {7.0, 0.4}));
    s.obstacles.push_back(Obstacle::makeBox({11.5, y}, {1.0, 0.4}));
  }
  RobotSpec r;
  r.name = "d";
  r.kind = RobotKind::Mobile;
  r.shape = MobileShape::Disc;
  r.radius = 0.3;
  r.start = {1, 1, 0};
  r.goal = {1, 11, 0};
  s.robots = {r};
  const RobotModels models(s);
  const CollisionWorld world(s);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> coord(0.5, 11.5);
  int compared = 0;
  for (int trial = 0; trial < 12; ++trial) {
    Roadmap rm(world, *models.raw[0], 10, static_cast<std::uint64_t>(trial) + 1);
    rm.grow(1500);
    QueryGraph lazy(rm, *models.raw[0]);
    double a[3] = {coord(rng), coord(rng), 0.0}, b[3] = {coord(rng), coord(rng), 0.0};
    if (!world.stateValid(*models.raw[0], a) || !world.stateValid(*models.raw[0], b)) continue;
    const int la = lazy.addVertex(a, 10), lb = lazy.addVertex(b, 10);
    const auto path = shortestPath(lazy, la, lb, Deadline());
    Roadmap fresh(world, *models.raw[0], 10, static_cast<std::uint64_t>(trial) + 1);
    fresh.grow(1500);
    QueryGraph eager(fresh, *models.raw[0]);
    const int ea = eager.addVertex(a, 10), eb = eager.addVertex(b, 10);
    const long long want = eagerSteps(eager, ea, eb);
    REQUIRE(path.has_value() == (want >= 0));
    if (!path) continue;
    CHECK(path->front() == la);
    CHECK(path->back() == lb);
    bool valid = false;
    CHECK(pathSteps(lazy, *path, valid) == want);
    CHECK(valid);
    ++compared;
  }
  CHECK(compared >= 6);
}

}  // namespace
}  // namespace earc
