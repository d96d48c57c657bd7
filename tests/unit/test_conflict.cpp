// Conflict detection: the first conflict between time-stamped paths, and
// paths checked against moving robots.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/generators.hpp"
#include "earc/planning/arc.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/planning/planner.hpp"
#include "earc/util/kdtree.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"

using earc::test::fiveLinkArm;
using earc::test::line;

using namespace earc;

#include "arc_fixtures.hpp"

using namespace earc::arc_test;

TEST_CASE("FindConflict catches two discs that touch only at the midpoint of a step") {
  const MidpointSwap swap;
  RobotModels m(swap.s);
  const std::vector<Path>& paths = swap.paths;
  ConflictDetector det(m.raw);
  auto c = det.first(pathPointers(paths));
  REQUIRE(c.has_value());
  CHECK(c->t == doctest::Approx(0.5));
  CHECK(c->a == 0);
  CHECK(c->b == 1);
  CHECK(c->place.x == doctest::Approx(1.2));
}

TEST_CASE("FindConflict reports nothing for discs that pass with clearance") {
  Scenario s = openScenario(5);
  s.robots = {disc("a", 0.1, {1, 1, 0}, {2, 1, 0}), disc("b", 0.1, {1, 1.3, 0}, {2, 1.3, 0})};
  RobotModels m(s);
  std::vector<Path> paths{line({{1, 1, 0}, {1.05, 1, 0}, {1.1, 1, 0}}), line({{1, 1.3, 0}, {1.05, 1.3, 0}})};
  ConflictDetector det(m.raw);
  CHECK_FALSE(det.first(pathPointers(paths)).has_value());
}

TEST_CASE("FindConflict given a deadline that has passed gives up and says so, rather than report no conflict") {
  const MidpointSwap swap;
  RobotModels m(swap.s);
  const std::vector<Path>& paths = swap.paths;
  const Deadline later(1e6), past(-1.0);
  ConflictDetector in_time(m.raw, later);
  CHECK(in_time.first(pathPointers(paths)).has_value());
  CHECK_FALSE(in_time.interrupted());
  ConflictDetector late(m.raw, past);
  CHECK_FALSE(late.first(pathPointers(paths)).has_value());
  CHECK(late.interrupted());
}

TEST_CASE("FindConflict sees a robot that waits at its goal after its path ends") {
  Scenario s = openScenario(5);
  s.robots = {disc("a", 0.2, {1, 1, 0}, {1, 1, 0}), disc("b", 0.2, {2, 1, 0}, {1.3, 1, 0})};
  RobotModels m(s);
  std::vector<Path> paths{line({{1, 1, 0}}), line({{2, 1, 0}, {1.8, 1, 0}, {1.6, 1, 0}, {1.3, 1, 0}})};
  ConflictDetector det(m.raw);
  auto c = det.first(pathPointers(paths));
  REQUIRE(c.has_value());
  // At the midpoint of steps 2-3 b is at 1.45, 0.45 from a: apart. At step
  // 3 it is at 1.3, 0.3 from a: touching (radii sum 0.4).
  CHECK(c->t == doctest::Approx(3.0));
}

TEST_CASE("FindConflict with its broad phase agrees with all-pairs checking on random paths") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.5, 19.5);
  Scenario s = openScenario(20);
  const int n = 40, steps = 60;
  std::vector<Path> paths;
  for (int i = 0; i < n; ++i) {
    double x = u(rng), y = u(rng), dx = (u(rng) - 10) * 0.004, dy = (u(rng) - 10) * 0.004;
    s.robots.push_back(disc("r" + std::to_string(i), 0.3, {x, y, 0}, {x + dx * steps, y + dy * steps, 0}));
    Path p(3);
    for (int t = 0; t <= steps; ++t) {
      double q[3] = {x + dx * t, y + dy * t, 0};
      p.push(q);
    }
    paths.push_back(std::move(p));
  }
  RobotModels m(s);
  // Brute force: earliest instant, then lowest pair.
  std::optional<std::tuple<double, int, int>> expect;
  for (int k = 0; k <= 2 * steps && !expect; ++k) {
    for (int i = 0; i < n && !expect; ++i)
      for (int j = i + 1; j < n; ++j) {
        double qi[3], qj[3];
        stateAtInstant(*m.raw[i], paths[i], k, qi);
        stateAtInstant(*m.raw[j], paths[j], k, qj);
        if (robotsTouch(*m.raw[i], qi, *m.raw[j], qj)) {
          expect = std::make_tuple(k / 2.0, i, j);
          break;
        }
      }
  }
  ConflictDetector det(m.raw);
  auto c = det.first(pathPointers(paths));
  REQUIRE(c.has_value() == expect.has_value());
  if (c) {
    CHECK(c->t == doctest::Approx(std::get<0>(*expect)));
    CHECK(c->a == std::get<1>(*expect));
    CHECK(c->b == std::get<2>(*expect));
  }
}

TEST_CASE("FindConflict agrees with all-pairs checking on wandering boxes and arms, in windows and with a focus") {
  // Boxes turn as they go and arms sweep their links, some standing still
  // for a while, over more instants than one chunk of the detector's
  // broad phase, which must never skip the earliest touching pair. The
  // arms stand apart from the boxes, so that only their own bounds let
  // them be checked.
  Scenario s = fourBoxes();
  s.workspace = {{0, 0}, {18, 6}};
  for (int i = 0; i < 4; ++i)
    s.robots.push_back(fiveLinkArm("arm" + std::to_string(i), {12.0 + 2.2 * (i % 2), 1.0 + 4.0 * (i / 2)}, i % 2 ? 3.14159 : 0.0,
                           {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}));
  RobotModels m(s);
  const std::size_t n = m.raw.size();
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> pos(1.0, 5.0), step(-0.05, 0.05), ang(-3.0, 3.0), turn(-0.06, 0.06),
      unit(0.0, 1.0);
  auto walk = [&](const RobotModel& model, std::size_t steps) {
    std::vector<double> q(static_cast<std::size_t>(model.dim()));
    for (double& v : q) v = model.isMobile() ? ang(rng) : 0.5 * ang(rng);
    if (model.isMobile()) q[0] = pos(rng), q[1] = pos(rng);
    Path p(model.dim());
    const std::size_t rest_from = steps / 3, rest_to = rest_from + static_cast<std::size_t>(unit(rng) * 30);
    for (std::size_t t = 0; t <= steps; ++t) {
      p.push(q.data());
      if (t >= rest_from && t < rest_to) continue;
      for (std::size_t d = 0; d < q.size(); ++d) q[d] += (model.isMobile() && d < 2) ? step(rng) : turn(rng);
    }
    return p;
  };
  int found = 0, none = 0;
  for (int trial = 0; trial < 150; ++trial) {
    std::vector<Path> paths;
    for (std::size_t r = 0; r < n; ++r) paths.push_back(walk(*m.raw[r], 20 + static_cast<std::size_t>(trial) % 60));
    std::vector<char> focus(n, 0);
    focus[static_cast<std::size_t>(trial) % n] = 1;
    const bool focused = trial % 2 == 1;
    const std::size_t from = static_cast<std::size_t>(trial) % 7, to = from + 10 + static_cast<std::size_t>(trial) % 50;
    std::size_t horizon = 0;
    for (const Path& p : paths) horizon = std::max(horizon, p.size() - 1);
    std::optional<std::tuple<double, int, int>> expect;
    std::vector<double> qi(5), qj(5);
    for (std::size_t k = 2 * from; k <= 2 * std::min(to, horizon) && !expect; ++k)
      for (std::size_t i = 0; i < n && !expect; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
          if (focused && !focus[i] && !focus[j]) continue;
          stateAtInstant(*m.raw[i], paths[i], k, qi.data());
          stateAtInstant(*m.raw[j], paths[j], k, qj.data());
          if (robotsTouch(*m.raw[i], qi.data(), *m.raw[j], qj.data())) {
            expect = std::make_tuple(static_cast<double>(k) / 2.0, static_cast<int>(i), static_cast<int>(j));
            break;
          }
        }
    ConflictDetector det(m.raw);
    auto c = det.first(pathPointers(paths), from, to, focused ? &focus : nullptr);
    REQUIRE(c.has_value() == expect.has_value());
    if (c) {
      CHECK(c->t == std::get<0>(*expect));
      CHECK(c->a == std::get<1>(*expect));
      CHECK(c->b == std::get<2>(*expect));
    }
    (c ? found : none) += 1;
  }
  CHECK(found > 30);
  CHECK(none > 30);
}

TEST_CASE("clearOfMoving agrees with an instant-by-instant check on random box and arm motions") {
  // Boxes turn as they move and arms sweep their links, so the checks meet
  // near misses of the bounding discs that only the exact bodies decide.
  Scenario s = fourBoxes();
  s.robots.push_back(fiveLinkArm("armA", {2, 3}, 0.0, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}));
  s.robots.push_back(fiveLinkArm("armB", {4.2, 3}, 3.14159, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}));
  RobotModels m(s);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> pos(1.0, 5.0), step(-0.12, 0.12), ang(-3.0, 3.0), turn(-0.3, 0.3);
  auto walk = [&](const RobotModel& model, std::size_t steps) {
    std::vector<double> q(static_cast<std::size_t>(model.dim()));
    for (double& v : q) v = model.isMobile() ? ang(rng) : 0.6 * ang(rng) / 3.0;
    if (model.isMobile()) q[0] = pos(rng), q[1] = pos(rng);
    Path p(model.dim());
    for (std::size_t t = 0; t <= steps; ++t) {
      p.push(q.data());
      for (std::size_t d = 0; d < q.size(); ++d) q[d] += (model.isMobile() && d < 2) ? step(rng) : turn(rng);
    }
    return p;
  };
  int clear = 0, blocked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const std::size_t self = static_cast<std::size_t>(trial) % 6;
    const RobotModel& model = *m.raw[self];
    const Path local = walk(model, 12);
    std::vector<Path> others;
    std::vector<std::size_t> who;
    for (std::size_t r = 0; r < 6; ++r)
      if (r != self && (self < 4) == (r < 4)) {  // boxes meet boxes, arms meet arms
        others.push_back(walk(*m.raw[r], 4 + static_cast<std::size_t>(trial) % 20));
        who.push_back(r);
      }
    std::vector<MovingObstacle> obstacles;
    for (std::size_t i = 0; i < others.size(); ++i)
      obstacles.push_back({m.raw[who[i]], &others[i], static_cast<std::size_t>(trial) % 3, static_cast<int>(who[i])});
    bool expect = true;
    std::vector<double> q(static_cast<std::size_t>(model.dim())), oq(12);
    for (std::size_t k = 0; k <= 2 * (local.size() - 1) && expect; ++k) {
      stateAtInstant(model, local, k, q.data());
      for (const MovingObstacle& o : obstacles) {
        stateAtInstant(*o.model, *o.path, 2 * o.offset + k, oq.data());
        if (robotsTouch(model, q.data(), *o.model, oq.data())) expect = false;
      }
    }
    CHECK(clearOfMoving(model, local, obstacles) == expect);
    (expect ? clear : blocked) += 1;
  }
  CHECK(clear > 40);
  CHECK(blocked > 40);
}
