// Scenarios, fixtures and checks shared by the ARC tests (test_arc.cpp,
// test_conflict.cpp, test_decoupled.cpp, test_roadmap_search.cpp).
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/arc.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/planning/planner.hpp"
#include "support.hpp"

namespace earc::arc_test {

using earc::test::line;

inline RobotSpec disc(const std::string& name, double r, std::vector<double> start, std::vector<double> goal) {
  RobotSpec s;
  s.name = name;
  s.kind = RobotKind::Mobile;
  s.shape = MobileShape::Disc;
  s.radius = r;
  s.start = std::move(start);
  s.goal = std::move(goal);
  return s;
}

inline Scenario openScenario(double size) {
  Scenario s;
  s.name = "test";
  s.workspace = {{0, 0}, {size, size}};
  return s;
}

// A 6 x 6 square with four 0.6 x 0.4 box robots (starts and goals are the
// caller's to set, or unused).
inline Scenario fourBoxes() {
  Scenario s = openScenario(6);
  for (int i = 0; i < 4; ++i) {
    RobotSpec b = RobotSpec::mobileBox("box" + std::to_string(i), {0.6, 0.4});
    b.start = b.goal = {0, 0, 0};
    s.robots.push_back(b);
  }
  return s;
}

// Two discs that swap places in one step, touching only at its midpoint.
struct MidpointSwap {
  Scenario s;
  std::vector<Path> paths{line({{1.0, 1.0, 0}, {1.4, 1.0, 0}}), line({{1.4, 1.0, 0}, {1.0, 1.0, 0}})};
  MidpointSwap() : s(openScenario(5)) {
    s.resolution.translation = 0.5;
    s.robots = {disc("a", 0.1, {1.0, 1.0, 0}, {1.4, 1.0, 0}), disc("b", 0.1, {1.4, 1.0, 0}, {1.0, 1.0, 0})};
  }
};

// Robot 0 of a scenario, and a roadmap of `vertices` vertices for it in
// the scenario's world: what the space-time search's tests search on.
struct SearchWorld {
  RobotModels m;
  CollisionWorld world;
  Roadmap rm;
  SearchWorld(const Scenario& s, int vertices) : m(s), world(s), rm(world, *m.raw[0], 10, 3) { rm.grow(vertices); }
  const RobotModel& model() const { return *m.raw[0]; }
};

// Two discs a and b on straight, crossing paths through (5, 5): their
// models, the world, and the paths' first conflict, from which the
// subproblem tests start; with a bystander radius, a third disc c of that
// radius rests at (9, 9), out of their way. (Members are made in this
// order: each from those above it.)
struct CrossingFixture {
  explicit CrossingFixture(double bystander_radius = 0)
      : s(scenario(bystander_radius)), paths(crossingPaths(bystander_radius)), m(s), world(s), c(firstConflict()) {}
  Scenario s;
  std::vector<Path> paths;
  RobotModels m;
  CollisionWorld world;
  Conflict c;

  // a's and b's subproblem of the conflict at `level`, as the paths are now.
  Subproblem subproblem(const PlannerSettings& settings, int level = 0) const {
    return createSubproblem(c, {0, 1}, level, m.raw, paths, world, settings);
  }

 private:
  static Scenario scenario(double bystander_radius) {
    Scenario sc = openScenario(10);
    sc.robots = {disc("a", 0.2, {3, 5, 0}, {7, 5, 0}), disc("b", 0.2, {5, 3, 0}, {5, 7, 0})};
    if (bystander_radius > 0) sc.robots.push_back(disc("c", bystander_radius, {9, 9, 0}, {9, 9, 0}));
    return sc;
  }
  static std::vector<Path> crossingPaths(double bystander_radius) {
    std::vector<Path> out;
    for (int r = 0; r < 2; ++r) {
      Path p(3);
      for (int t = 0; t <= 80; ++t) {
        double q[3] = {r == 0 ? 3 + 0.05 * t : 5.0, r == 0 ? 5.0 : 3 + 0.05 * t, 0};
        p.push(q);
      }
      out.push_back(std::move(p));
    }
    if (bystander_radius > 0) out.push_back(line({9, 9, 0}, {9, 9, 0}, 81));
    return out;
  }
  Conflict firstConflict() const {
    ConflictDetector det(m.raw);
    auto found = det.first(pathPointers(paths));
    REQUIRE(found.has_value());
    return *found;
  }
};


// Plans `model` from start to goal on `rm` among moving obstacles with
// the space-time search, and checks the path it returns instant by
// instant against their exact bodies. Tallies paths found, those that
// arrive later than the robot alone would, and searches that found none.
struct SearchTally {
  int found = 0, delayed = 0, none = 0;
};
inline void searchAmongMoving(Roadmap& rm, const RobotModel& model, const double* start, const double* goal,
                       const std::vector<MovingObstacle>& obstacles, std::size_t horizon, SearchTally& tally) {
  QueryGraph graph(rm, model);
  const int sv = graph.addVertex(start, 10), gv = graph.addVertex(goal, 10);
  auto alone = spaceTimeSearch(graph, sv, gv, {}, horizon, 0, Deadline(), 1000000);
  auto path = spaceTimeSearch(graph, sv, gv, obstacles, horizon, 0, Deadline(), 1000000);
  if (!path) {
    ++tally.none;
    return;
  }
  ++tally.found;
  REQUIRE(alone);
  if (path->size() > alone->size()) ++tally.delayed;
  const auto dim = static_cast<std::size_t>(model.dim());
  CHECK(std::equal(start, start + dim, path->at(0)));
  std::vector<double> q(dim), oq;
  for (std::size_t k = 0; k <= 2 * (path->size() - 1); ++k) {
    CAPTURE(k);
    stateAtInstant(model, *path, k, q.data());
    for (const MovingObstacle& o : obstacles) {
      oq.resize(static_cast<std::size_t>(o.model->dim()));
      stateAtInstant(*o.model, *o.path, k, oq.data());
      CHECK_FALSE(robotsTouch(model, q.data(), *o.model, oq.data()));
    }
  }
}

}  // namespace earc::arc_test
