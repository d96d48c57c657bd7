// ARC: conflict detection, subproblem windows, expansion, merging, splicing,
// and whole plans that must validate.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/generators.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/arc.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/planning/planner.hpp"
#include "earc/util/kdtree.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"

using earc::test::fiveLinkArm;
using earc::test::line;

using namespace earc;

namespace {

RobotSpec disc(const std::string& name, double r, std::vector<double> start, std::vector<double> goal) {
  RobotSpec s;
  s.name = name;
  s.kind = RobotKind::Mobile;
  s.shape = MobileShape::Disc;
  s.radius = r;
  s.start = std::move(start);
  s.goal = std::move(goal);
  return s;
}

Scenario openScenario(double size) {
  Scenario s;
  s.name = "test";
  s.workspace = {{0, 0}, {size, size}};
  return s;
}

// A 6 x 6 square with four 0.6 x 0.4 box robots (starts and goals are the
// caller's to set, or unused).
Scenario fourBoxes() {
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

}  // namespace

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

namespace {

// Two discs on straight, crossing paths through (5, 5): their models, the
// world, and the paths' first conflict, from which the subproblem tests
// start. (Members are made in this order: each from those above it.)
// Robot 0 of a scenario, and a roadmap of `vertices` vertices for it in
// the scenario's world: what the space-time search's tests search on.
struct SearchWorld {
  RobotModels m;
  CollisionWorld world;
  Roadmap rm;
  SearchWorld(const Scenario& s, int vertices) : m(s), world(s), rm(world, *m.raw[0], 10, 3) { rm.grow(vertices); }
  const RobotModel& model() const { return *m.raw[0]; }
};

// Discs a and b cross at (5, 5); with a bystander radius, a third disc c
// of that radius rests at (9, 9), out of their way.
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

}  // namespace

TEST_CASE("A subproblem's window spans the conflict and its local query lies on the paths") {
  CrossingFixture f;
  PlannerSettings settings;
  settings.initial_window = 8;
  Subproblem sub = f.subproblem(settings);
  CHECK(sub.t_start + 8 == static_cast<std::size_t>(f.c.t));
  CHECK(sub.t_end >= static_cast<std::size_t>(f.c.t) + 8);
  // The end moved past the crossing so that the local goals are apart.
  CHECK_FALSE(robotsTouch(*f.m.raw[0], sub.goals[0].data(), *f.m.raw[1], sub.goals[1].data()));
  for (int r = 0; r < 2; ++r) {
    CHECK(sub.starts[r] == std::vector<double>(f.paths[r].at(sub.t_start), f.paths[r].at(sub.t_start) + 3));
    CHECK(sub.region[r].contains(sub.starts[r].data()));
    CHECK(sub.region[r].contains(sub.goals[r].data()));
  }
  CHECK_FALSE(sub.whole_problem);
}

TEST_CASE("The decoupled solver builds its robots' roadmaps before its time budget starts") {
  // The discs' straight paths need no roadmap; the solver needs them, and
  // building them is not the search's time: with a budget of zero the
  // search gives up at once, yet the roadmap is there.
  CrossingFixture f;
  PlannerSettings settings;
  Subproblem sub = f.subproblem(settings);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  REQUIRE(roadmaps.built() == 0);
  SolverContext ctx{f.world, f.m.raw, roadmaps, f.paths, sub, Deadline(10), 7};
  DecoupledSettings none;
  none.time_budget_s = 0;
  CHECK_FALSE(DecoupledSolver(none).solve(ctx).solution.has_value());
  CHECK(roadmaps.built() == 1);  // equal discs share one
  // With time, the same subproblem is solved on that roadmap.
  CHECK(DecoupledSolver().solve(ctx).solution.has_value());
  CHECK(roadmaps.built() == 1);
}

TEST_CASE("Expanding a subproblem doubles its window and grows its region until it is the whole problem") {
  CrossingFixture f;
  PlannerSettings settings;
  settings.initial_window = 4;
  settings.max_expansions = 5;
  Subproblem a = f.subproblem(settings);
  Subproblem b = f.subproblem(settings, 1);
  CHECK(a.t_start - b.t_start == 4);
  CHECK(b.region[0].hi[0] - b.region[0].lo[0] > a.region[0].hi[0] - a.region[0].lo[0]);
  Subproblem last = f.subproblem(settings, 5);
  CHECK(last.whole_problem);
  CHECK(last.t_start == 0);
  CHECK(last.t_end == 80);
  CHECK(last.goals[0] == f.s.robots[0].goal);
}

TEST_CASE("A subproblem whose window and regions already cover everything is the whole problem before the last level") {
  // Retrying it level by level would solve the same subproblem again with
  // the same budgets; marked whole, ARC goes on to larger budgets.
  CrossingFixture f;
  PlannerSettings settings;
  settings.initial_window = 4;
  settings.max_expansions = 12;
  int first_saturated = -1;
  for (int level = 0; level <= settings.max_expansions; ++level) {
    CAPTURE(level);
    Subproblem sub = f.subproblem(settings, level);
    bool covers = sub.t_start == 0 && sub.t_end == 80;
    for (int r = 0; r < 2; ++r) {
      ConfigBox full;
      f.m.raw[static_cast<std::size_t>(r)]->samplingBounds(f.world.workspace(), full.lo, full.hi);
      covers = covers && sub.region[static_cast<std::size_t>(r)].lo == full.lo &&
               sub.region[static_cast<std::size_t>(r)].hi == full.hi;
    }
    CHECK(sub.whole_problem == (covers || level == settings.max_expansions));
    if (covers && first_saturated < 0) first_saturated = level;
  }
  CHECK(first_saturated > 0);
  CHECK(first_saturated < settings.max_expansions);
}

TEST_CASE("A subproblem spanning the paths whose regions together span the workspace is the whole problem") {
  // Robot a's own region is not yet the full box, but the regions together
  // cover the workspace: the levels left would only widen a's region a
  // margin a level, each at the same budget.
  CrossingFixture f;
  PlannerSettings settings;
  settings.initial_window = 64;  // the window spans both paths from level 0
  settings.max_expansions = 12;
  ConfigBox full;
  f.m.raw[0]->samplingBounds(f.world.workspace(), full.lo, full.hi);
  Subproblem one = f.subproblem(settings, 1);
  REQUIRE(one.t_start == 0);
  REQUIRE(one.t_end == 80);
  CHECK_FALSE(one.whole_problem);
  Subproblem two = f.subproblem(settings, 2);
  CHECK(two.whole_problem);
  CHECK_FALSE(two.region[0] == full);
}

TEST_CASE("The decoupled solver's expansion cap grows with the hierarchy's budget scale") {
  // Past ARC's last level the same subproblem is retried with a larger
  // budget scale: a search cut off by its expansion cap must get further.
  CrossingFixture f;
  PlannerSettings settings;
  Subproblem sub = f.subproblem(settings);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  DecoupledSettings tight;
  tight.max_expansions = 3;
  tight.expansions_per_horizon_step = 0;
  tight.avoid_others = false;
  SolverContext ctx{f.world, f.m.raw, roadmaps, f.paths, sub, Deadline(10), 7};
  CHECK_FALSE(DecoupledSolver(tight).solve(ctx).solution.has_value());
  ctx.budget_scale = 2000;
  CHECK(DecoupledSolver(tight).solve(ctx).solution.has_value());
}

TEST_CASE("A robot with no way past the robots outside its group ends the decoupled attempt at once") {
  // Discs a and b cross; disc c rests for good where a's window ends. a,
  // planned first, finds no way to hold its goal; behind b it would find
  // none either, so the solver says so and tries no other order.
  CrossingFixture f(0.2);
  PlannerSettings settings;
  const Subproblem sub = f.subproblem(settings);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  SolverContext ctx{f.world, f.m.raw, roadmaps, f.paths, sub, Deadline(10), 7};
  REQUIRE(DecoupledSolver().solve(ctx).solution.has_value());  // with c out of the way
  f.paths[2] = Path(3);
  for (int t = 0; t <= 80; ++t) f.paths[2].push(sub.goals[0].data());
  const SolverOutcome out = DecoupledSolver().solve(ctx);
  CHECK_FALSE(out.solution.has_value());
  CHECK(out.detail == "robot 0 has no way past the robots outside the group, in any order");

  // The search says whether it ran out of ways or stopped short of them.
  QueryGraph graph(roadmaps.forRobot(0), *f.m.raw[0], &sub.region[0]);
  const int sv = graph.addVertex(sub.starts[0].data(), 10), gv = graph.addVertex(sub.goals[0].data(), 10);
  const std::vector<MovingObstacle> resting{{f.m.raw[2], &f.paths[2], sub.t_start, 2}};
  const std::size_t window = sub.t_end - sub.t_start;
  SearchEnd end = SearchEnd::Found;
  CHECK_FALSE(spaceTimeSearch(graph, sv, gv, resting, 200, window, Deadline(), 100000, false, &end));
  CHECK(end == SearchEnd::NoWay);
  CHECK_FALSE(spaceTimeSearch(graph, sv, gv, {}, 200, window, Deadline(), 0, false, &end));
  CHECK(end == SearchEnd::Capped);
  CHECK_FALSE(spaceTimeSearch(graph, sv, gv, {}, 200, window, Deadline(-1.0), 100000, false, &end));
  CHECK(end == SearchEnd::OutOfTime);
  CHECK(spaceTimeSearch(graph, sv, gv, {}, 200, window, Deadline(), 100000, false, &end));
  CHECK(end == SearchEnd::Found);
}

TEST_CASE("The decoupled solver's robots arrive within the window and 50 steps, more on the hierarchy's retries") {
  // Discs a and b cross; disc c rests on a's way, in a region too narrow
  // to pass it, until 80 steps after the window: a can get by only after
  // that, later than its horizon allows.
  CrossingFixture f(0.1);
  PlannerSettings settings;
  settings.region_margin = 0.2;
  settings.initial_window = 16;
  const Subproblem sub = f.subproblem(settings);
  const std::size_t window = sub.t_end - sub.t_start;
  f.paths[2] = Path(3);
  const double in_the_way[3] = {4.5, 5, 0}, away[3] = {9, 9, 0};
  for (std::size_t t = 0; t <= sub.t_end + 80; ++t) f.paths[2].push(in_the_way);
  f.paths[2].push(away);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  SolverContext ctx{f.world, f.m.raw, roadmaps, f.paths, sub, Deadline(10), 7};
  CHECK_FALSE(DecoupledSolver().solve(ctx).solution.has_value());
  DecoupledSettings patient;
  patient.horizon_steps = 200;
  const SolverOutcome waited = DecoupledSolver(patient).solve(ctx);
  REQUIRE(waited.solution.has_value());
  CHECK(waited.solution->length() > window + 80);
  // Past ARC's last level the budget scale grows the horizon too.
  ctx.budget_scale = 4;
  CHECK(DecoupledSolver().solve(ctx).solution.has_value());
}

TEST_CASE("A failed decoupled attempt says how its last priority order failed") {
  // Two discs swap places along a line, in a region too narrow to pass:
  // either one, planned first, goes straight through; the other then has
  // no way past it, in both orders.
  Scenario s = openScenario(10);
  s.robots = {disc("a", 0.2, {3, 5, 0}, {7, 5, 0}), disc("b", 0.2, {7, 5, 0}, {3, 5, 0})};
  RobotModels m(s);
  CollisionWorld world(s);
  std::vector<Path> paths{line({3, 5, 0}, {7, 5, 0}, 81), line({7, 5, 0}, {3, 5, 0}, 81)};
  auto conflict = ConflictDetector(m.raw).first(pathPointers(paths));
  REQUIRE(conflict.has_value());
  PlannerSettings settings;
  settings.region_margin = 0.2;
  const Subproblem sub = createSubproblem(*conflict, {0, 1}, 0, m.raw, paths, world, settings);
  RoadmapSet roadmaps(world, m.raw, 300, 10, 1);
  SolverContext ctx{world, m.raw, roadmaps, paths, sub, Deadline(10), 7};
  const SolverOutcome out = DecoupledSolver().solve(ctx);
  CHECK_FALSE(out.solution.has_value());
  CHECK(out.detail == "2 priority orders failed; in the last, robot 0 (2 of 2): no way");
}

TEST_CASE("After a failed priority order the robot that failed goes first, and no order is tried twice") {
  std::mt19937_64 rng(5);
  using Order = std::vector<std::size_t>;
  // Robot 2 found no way behind 0 and 1: it picks its way first next.
  CHECK(nextPriorityOrder({{0, 1, 2}}, 2, rng) == Order{2, 0, 1});
  CHECK(nextPriorityOrder({{3, 1, 0, 2}}, 0, rng) == Order{0, 3, 1, 2});
  // The robot planned first failed (out of expansions): moving it to the
  // front gives the same order, so an untried one comes instead.
  std::vector<Order> tried{{0, 1, 2}};
  for (int k = 0; k < 5; ++k) {
    const Order next = nextPriorityOrder(tried, tried.back().front(), rng);
    REQUIRE(next.size() == 3);
    CHECK(std::find(tried.begin(), tried.end(), next) == tried.end());
    CHECK(std::is_permutation(next.begin(), next.end(), tried.front().begin()));
    tried.push_back(next);
  }
  // All 6 orders of 3 robots tried: none is left.
  CHECK(nextPriorityOrder(tried, 1, rng).empty());
  // Beyond 5 robots an untried order is drawn by shuffling.
  std::vector<Order> many{{0, 1, 2, 3, 4, 5, 6}};
  const Order next = nextPriorityOrder(many, 0, rng);
  CHECK(next != many.front());
  CHECK(std::is_permutation(next.begin(), next.end(), many.front().begin()));
  // Every order of 6 robots tried (a whole-problem prioritized plan may
  // try up to 1,000): none is left, and the search for one ends.
  std::vector<Order> all;
  Order six{0, 1, 2, 3, 4, 5};
  do all.push_back(six);
  while (std::next_permutation(six.begin(), six.end()));
  CHECK(nextPriorityOrder(all, 3, rng).empty());
  all.pop_back();
  CHECK(nextPriorityOrder(all, 3, rng) == Order{5, 4, 3, 2, 1, 0});
}

TEST_CASE("The decoupled solver tries each priority order of a group once at most") {
  // Three discs cross; no search may expand a state, so every order fails
  // at the robot planned first. Ten orders allowed, six exist.
  Scenario s = openScenario(10);
  s.robots = {disc("a", 0.2, {3, 5, 0}, {7, 5, 0}), disc("b", 0.2, {5, 3, 0}, {5, 7, 0}),
              disc("c", 0.2, {3.2, 4.6, 0}, {7.2, 5.4, 0})};
  RobotModels m(s);
  CollisionWorld world(s);
  std::vector<Path> paths{line({3, 5, 0}, {7, 5, 0}, 81), line({5, 3, 0}, {5, 7, 0}, 81),
                          line({3.2, 4.6, 0}, {7.2, 5.4, 0}, 81)};
  auto conflict = ConflictDetector(m.raw).first(pathPointers(paths));
  REQUIRE(conflict.has_value());
  PlannerSettings settings;
  const Subproblem sub = createSubproblem(*conflict, {0, 1, 2}, 0, m.raw, paths, world, settings);
  RoadmapSet roadmaps(world, m.raw, 300, 10, 1);
  SolverContext ctx{world, m.raw, roadmaps, paths, sub, Deadline(10), 7};
  DecoupledSettings capped;
  capped.max_expansions = 0;
  capped.max_orders = 10;
  const SolverOutcome out = DecoupledSolver(capped).solve(ctx);
  CHECK_FALSE(out.solution.has_value());
  CHECK(out.detail.rfind("6 priority orders failed; in the last, robot ", 0) == 0);
  CHECK(out.detail.find("(1 of 3): expansion cap") != std::string::npos);
}

TEST_CASE("Told to ignore the robots outside, the decoupled solver plans through one that walls its group in") {
  // ARC's retries of a whole problem do so every other time: the robot in
  // the way then meets the answer as a conflict of its own.
  CrossingFixture f;
  std::vector<Path> paths = f.paths;
  Path parked(3);  // robot b at rest across a's way for good
  for (int t = 0; t <= 80; ++t) {
    const double q[3] = {5, 5, 0};
    parked.push(q);
  }
  paths[1] = parked;
  PlannerSettings settings;
  settings.initial_window = 16;
  settings.region_margin = 0.2;  // too narrow a region to pass b
  Subproblem sub = createSubproblem(f.c, {0}, 0, f.m.raw, paths, f.world, settings);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  SolverContext ctx{f.world, f.m.raw, roadmaps, paths, sub, Deadline(10), 7};
  const SolverOutcome avoiding = DecoupledSolver().solve(ctx);
  CHECK_FALSE(avoiding.solution.has_value());
  ctx.ignore_others = true;
  const SolverOutcome ignoring = DecoupledSolver().solve(ctx);
  REQUIRE(ignoring.solution.has_value());
  const std::vector<MovingObstacle> b{{f.m.raw[1], &paths[1], sub.t_start, 1}};
  CHECK_FALSE(clearOfMoving(*f.m.raw[0], ignoring.solution->paths[0], b));
}

TEST_CASE("Splicing replaces the window and shifts the rest of the path in time") {
  Path p = line({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}});
  std::vector<Path> paths{p};
  Subproblem sub;
  sub.robots = {0};
  sub.t_start = 1;
  sub.t_end = 3;
  LocalSolution local;
  local.paths = {line({{1, 0, 0}, {1, 0, 0}, {1.5, 0, 0}, {2, 0, 0}, {2.5, 0, 0}, {3, 0, 0}})};
  splice(paths, sub, local);
  // One state before the window, six local states, one after.
  REQUIRE(paths[0].size() == 8);
  CHECK(paths[0].at(0)[0] == 0);
  CHECK(paths[0].at(2)[0] == 1);
  CHECK(paths[0].at(6)[0] == 3);
  CHECK(paths[0].at(7)[0] == 4);  // the old suffix, three steps later
}

TEST_CASE("Splicing a robot that had already finished pads its path with waits first") {
  std::vector<Path> paths{line({{0, 0, 0}, {1, 0, 0}})};
  Subproblem sub;
  sub.robots = {0};
  sub.t_start = 4;
  sub.t_end = 6;
  LocalSolution local;
  local.paths = {line({{1, 0, 0}, {1, 1, 0}, {1, 0, 0}})};
  splice(paths, sub, local);
  REQUIRE(paths[0].size() == 7);
  CHECK(paths[0].at(4)[1] == 0);
  CHECK(paths[0].at(5)[1] == 1);
  CHECK(paths[0].at(6)[1] == 0);
}

TEST_CASE("Merging pulls in the robots of resolved spans that overlap in time and share a conflict robot") {
  std::vector<ResolvedSpan> spans{{{1, 4}, 10, 30}, {{4, 7}, 25, 40}, {{2, 9}, 0, 100}, {{1, 5}, 50, 60}};
  std::vector<int> robots{1, 3};
  int added = mergeOverlapping(robots, spans, 20, 28, 8);
  // {1,4} overlaps and shares 1 -> 4. {4,7} overlaps but shares only the
  // merged 4 (one hop, not transitive); {2,9} shares nothing; {1,5} is
  // later in time.
  CHECK(robots == std::vector<int>{1, 3, 4});
  CHECK(added == 1);
}

TEST_CASE("Merging skips a span that would make the group larger than the cap") {
  std::vector<ResolvedSpan> spans{{{1, 4, 5, 6}, 10, 30}, {{3, 8}, 10, 30}};
  std::vector<int> robots{1, 3};
  int added = mergeOverlapping(robots, spans, 20, 20, 4);
  CHECK(robots == std::vector<int>{1, 3, 8});
  CHECK(added == 1);
}

TEST_CASE("ARC plans four discs crossing in the open, and the solution validates") {
  Scenario s = openScenario(6);
  s.robots = {disc("w", 0.3, {1, 3, 0}, {5, 3, 0}), disc("e", 0.3, {5, 3, 3.14}, {1, 3, 0}),
              disc("s", 0.3, {3, 1, 1.57}, {3, 5, 0}), disc("n", 0.3, {3, 5, -1.57}, {3, 1, 0})};
  PlannerSettings settings;
  settings.time_limit_s = 30;
  settings.seed = 3;
  PlanResult r = plan(s, settings);
  REQUIRE(r.solution.solved);
  CHECK(r.failures.empty());
  CHECK(r.stats["conflicts"].get<int>() >= 1);
  ValidationReport v = validateSolution(s, r.solution);
  CHECK(v.valid);
}

TEST_CASE("A roadmap built when a solver first asks for it is counted apart from that solver's time") {
  // Two discs whose straight motions meet head-on: no roadmap for their
  // own paths; the decoupled solver builds the shared one for the conflict.
  Scenario s = openScenario(6);
  s.robots = {disc("w", 0.3, {1, 3, 0}, {5, 3, 0}), disc("e", 0.3, {5, 3, 3.14}, {1, 3, 0})};
  PlannerSettings settings;
  settings.seed = 2;
  settings.trace = true;
  PlanResult r = plan(s, settings);
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(s, r.solution).valid);
  CHECK(r.stats["roadmaps_built"].get<int>() == 1);
  const double building = r.stats["roadmap_build_s"].get<double>();
  CHECK(building > 0);
  // The attempt that built it says so, and its time_s leaves it out.
  double in_attempts = 0;
  for (const auto& e : r.trace["events"])
    if (e["type"] == "subproblem")
      for (const auto& a : e["attempts"]) in_attempts += a.value("roadmap_build_s", 0.0);
  CHECK(in_attempts == doctest::Approx(building));
  double solver_time = 0;
  for (const auto& [name, secs] : r.stats["solver_time_s"].items()) solver_time += secs.get<double>();
  CHECK(solver_time + building <= r.stats["planning_time_s"].get<double>());
}

TEST_CASE("ARC keeps trying a conflict that grew to the whole problem until the deadline, then says both why") {
  // Two discs must swap ends of a corridor too narrow to pass: no
  // subproblem can ever be solved. ARC must not give up early with time
  // left (it retries the whole problem with growing budgets), and must
  // report the time limit and the unsolved subproblem.
  Scenario s;
  s.name = "corridor";
  s.workspace = {{0, 0}, {6, 1}};
  s.robots = {disc("a", 0.3, {0.5, 0.5, 0}, {5.5, 0.5, 0}), disc("b", 0.3, {5.5, 0.5, 0}, {0.5, 0.5, 0})};
  PlannerSettings settings;
  settings.time_limit_s = 5.0;
  settings.max_expansions = 3;  // 64 steps each side: the whole 100-step paths
  PlanResult r = plan(s, settings);
  CHECK_FALSE(r.solution.solved);
  CHECK(r.failures.count(FailureCause::TimeLimit) == 1);
  CHECK(r.failures.count(FailureCause::SubproblemUnsolved) == 1);
  CHECK(r.stats["planning_time_s"].get<double>() >= 4.9);
  CHECK(r.stats["subproblems"].get<int>() > settings.max_expansions + 1);  // retried beyond the last level
  // Every window after the first was an expansion, though none solved.
  CHECK(r.stats["window_expansions"].get<int>() == r.stats["subproblems"].get<int>() - 1);
}

TEST_CASE("A solver answering with the wrong number of paths is a named error, not a corrupted plan") {
  // A buggy solver: one path for a two-robot subproblem.
  struct OnePath : SubproblemSolver {
    const char* name() const override { return "one-path"; }
    SolverOutcome solve(SolverContext& ctx) override {
      LocalSolution sol;
      sol.paths.push_back(line({ctx.sub.starts[0], ctx.sub.goals[0]}));
      return {std::move(sol), name(), -1};
    }
  };
  Scenario s = openScenario(6);
  s.robots = {disc("w", 0.3, {1, 3, 0}, {5, 3, 0}), disc("e", 0.3, {5, 3, 3.14}, {1, 3, 0})};
  PlannerSettings settings;
  settings.time_limit_s = 10;
  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy;
  hierarchy.push_back(std::make_unique<OnePath>());
  CHECK_THROWS_WITH_AS(runArc(s, settings, std::move(hierarchy)),
                       doctest::Contains("solver 'one-path' answered a subproblem of 2 robots with 1 paths"),
                       std::logic_error);
}

TEST_CASE("ARC's retries beyond the last level ignore the robots outside the group every other time") {
  // A solver that records what each attempt was told, and solves only when
  // told to ignore the other robots (as a group walled in by them would).
  struct Recorder : SubproblemSolver {
    std::vector<std::pair<bool, bool>>* seen;  // (whole problem, ignore others) per attempt
    explicit Recorder(std::vector<std::pair<bool, bool>>* s) : seen(s) {}
    const char* name() const override { return "recorder"; }
    SolverOutcome solve(SolverContext& ctx) override {
      seen->emplace_back(ctx.sub.whole_problem, ctx.ignore_others);
      if (!ctx.ignore_others) return {std::nullopt, name(), -1};
      return DecoupledSolver().solve(ctx);
    }
  };
  Scenario s = openScenario(6);
  s.robots = {disc("w", 0.3, {1, 3, 0}, {5, 3, 0}), disc("e", 0.3, {5, 3, 3.14}, {1, 3, 0}),
              disc("n", 0.3, {0.5, 5.5, 0}, {0.6, 5.5, 0})};
  PlannerSettings settings;
  settings.time_limit_s = 20;
  settings.max_expansions = 2;
  settings.initial_window = 64;  // the window spans the paths: level 2 is the whole problem
  settings.crowd_fallback = false;  // ARC's own retries, not a jam handed over
  std::vector<std::pair<bool, bool>> seen;
  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy;
  hierarchy.push_back(std::make_unique<Recorder>(&seen));
  PlanResult r = runArc(s, settings, std::move(hierarchy));
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(s, r.solution).valid);
  // Levels 0 to 2 (the last a whole problem) without ignoring, the first
  // retry beyond them ignoring, and solved there.
  REQUIRE(seen.size() >= 4);
  for (std::size_t i = 0; i + 1 < seen.size(); ++i) CHECK_FALSE(seen[i].second);
  CHECK(seen.back().first);
  CHECK(seen.back().second);
}

TEST_CASE("A conflict's merge cap grows by one robot every third time it comes back, up to four more") {
  ConflictRecurrence rec;
  std::vector<std::size_t> caps;
  // The same two robots in the same half-unit cell, at drifting instants:
  // every resolution shifts the later paths in time.
  for (int i = 0; i < 16; ++i) caps.push_back(rec.capFor({3, 7, 41.5 + 3 * i, {2.1 + 0.02 * i, 3.2}}, 5));
  CHECK(caps == std::vector<std::size_t>{5, 5, 5, 6, 6, 6, 7, 7, 7, 8, 8, 8, 9, 9, 9, 9});
  // Another cell, or another pair, is another conflict.
  CHECK(rec.capFor({3, 7, 41.5, {2.6, 3.2}}, 5) == 5);
  CHECK(rec.capFor({3, 7, 41.5, {2.1, 2.9}}, 5) == 5);
  CHECK(rec.capFor({3, 8, 41.5, {2.1, 3.2}}, 5) == 5);
  CHECK(rec.capFor({7, 3, 41.5, {2.1, 3.2}}, 2) == 6);  // the same pair either way round
}

TEST_CASE("Groups at the merge cap that undo each other grow until the plan is solved, instead of looping") {
  // Every solver here plans its group as if no other robot were there, as
  // the coupled solver does; with groups capped at two robots, each
  // answer runs into a robot of another group and undoes its resolution.
  // Eight 0.8-radius discs in an 8 x 8 square: with the cap fixed, this
  // plan looped until its 30 s limit; a conflict that comes back now takes
  // in the robot it keeps running into.
  struct Blinkered : SubproblemSolver {
    const char* name() const override { return "blinkered"; }
    SolverOutcome solve(SolverContext& ctx) override {
      ctx.ignore_others = true;
      return DecoupledSolver().solve(ctx);
    }
  };
  gen::MobileSettings crowd;
  crowd.robots = 8;
  crowd.workspace = 8;
  crowd.footprint.shape = MobileShape::Disc;
  crowd.footprint.radius = 0.8;
  crowd.seed = 5;
  const Scenario s = gen::generateMobile(crowd);
  PlannerSettings settings;
  settings.time_limit_s = 30;
  settings.crowd_fallback = false;  // the merge cap as published, not a jam handed over
  settings.max_merged_robots = 2;
  settings.work_budgets = true;  // the same plan under sanitizers
  settings.trace = true;
  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy;
  hierarchy.push_back(std::make_unique<Blinkered>());
  PlanResult r = runArc(s, settings, std::move(hierarchy));
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(s, r.solution).valid);
  CHECK(r.stats["merge_cap_raised"].get<int>() > 0);
  // A group past the cap only where the trace says its cap was raised.
  std::size_t largest = 0;
  for (const auto& ev : r.trace["events"]) {
    if (ev["type"] != "subproblem") continue;
    const std::size_t n = ev["robots"].size();
    largest = std::max(largest, n);
    if (n > 2) CHECK(ev.contains("merge_cap"));
  }
  CHECK(largest > 2);
}

TEST_CASE("ARC plans two facing arms whose straight motions collide, and the solution validates") {
  Scenario s;
  s.name = "arms";
  s.workspace = {{-4, -4}, {4, 8}};
  // Bases 4 apart facing each other; both reach for the middle and swap sides.
  s.robots = {fiveLinkArm("a", {0, 0}, 1.5708, {0.9, 0, 0, 0, 0}, {-0.9, 0, 0, 0, 0}),
              fiveLinkArm("b", {0, 4}, -1.5708, {0.9, 0, 0, 0, 0}, {-0.9, 0, 0, 0, 0})};
  PlannerSettings settings;
  settings.time_limit_s = 30;
  settings.seed = 5;
  PlanResult r = plan(s, settings);
  REQUIRE(r.solution.solved);
  ValidationReport v = validateSolution(s, r.solution);
  CHECK(v.valid);
}

TEST_CASE("Arms with nothing in reach share one roadmap; an arm near an obstacle or the workspace edge has its own") {
  Scenario s;
  s.name = "arms";
  s.workspace = {{-4, -4}, {12, 8}};
  s.robots = {fiveLinkArm("a", {0, 0}, 1.5708, {0.9, 0, 0, 0, 0}, {-0.9, 0, 0, 0, 0}),
              fiveLinkArm("b", {0, 4}, -1.5708, {0.9, 0, 0, 0, 0}, {-0.9, 0, 0, 0, 0}),
              fiveLinkArm("c", {6, 0}, 0.0, {0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0}),
              fiveLinkArm("d", {10.5, 4}, 0.0, {0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0})};
  s.obstacles.push_back(Obstacle::makeBox({7, 1.5}, {0.4, 0.4}));  // within c's reach (2.55)
  RobotModels m(s);
  CollisionWorld world(s);
  RoadmapSet roadmaps(world, m.raw, 50, 10, 1);
  CHECK(&roadmaps.forRobot(0) == &roadmaps.forRobot(1));  // facing each other, yet the same valid joint space
  CHECK(&roadmaps.forRobot(2) != &roadmaps.forRobot(0));  // an obstacle within reach
  CHECK(&roadmaps.forRobot(3) != &roadmaps.forRobot(0));  // its reach crosses the workspace edge
  CHECK(&roadmaps.forRobot(3) != &roadmaps.forRobot(2));
}

TEST_CASE("An arm with something in reach gets the free space's roadmap less what it cannot reach; the others keep theirs") {
  Scenario s;
  s.name = "arms";
  s.workspace = {{-4, -4}, {12, 8}};
  s.robots = {fiveLinkArm("a", {0, 0}, 1.5708, {0.9, 0, 0, 0, 0}, {-0.9, 0, 0, 0, 0}),
              fiveLinkArm("c", {6, 0}, 0.0, {0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0}),
              fiveLinkArm("d", {10.5, 4}, 0.0, {0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0})};
  s.obstacles.push_back(Obstacle::makeBox({7, 1.5}, {1.0, 1.0}));  // within c's reach
  RobotModels m(s);
  CollisionWorld world(s);
  RoadmapSet roadmaps(world, m.raw, 300, 10, 1);
  // The arm with nothing in reach: the roadmap it has without the others.
  Scenario alone = s;
  alone.robots.resize(1);
  RobotModels m_alone(alone);
  CollisionWorld world_alone(alone);
  RoadmapSet by_itself(world_alone, m_alone.raw, 300, 10, 1);
  Roadmap& free = roadmaps.forRobot(0);
  Roadmap& reference = by_itself.forRobot(0);
  REQUIRE(free.size() == reference.size());
  for (int v = 0; v < free.size(); ++v) {
    CHECK(std::equal(free.config(v), free.config(v) + 5, reference.config(v)));
    CHECK(free.edges(v).size() == reference.edges(v).size());
  }
  CHECK_FALSE(free.droppedAny());
  for (int robot : {1, 2}) {
    CAPTURE(robot);
    Roadmap& rm = roadmaps.forRobot(robot);
    const RobotModel& model = *m.raw[static_cast<std::size_t>(robot)];
    REQUIRE(rm.size() == free.size());
    int dropped = 0;
    for (int v = 0; v < rm.size(); ++v) {
      CHECK(std::equal(rm.config(v), rm.config(v) + 5, free.config(v)));
      // Dropped exactly where the arm's surroundings take the vertex.
      CHECK(rm.dropped(v) == !world.stateValid(model, rm.config(v)));
      if (rm.dropped(v)) {
        ++dropped;
        continue;
      }
      // A vertex left is joined to at least k others left, by edges not
      // marked invalid unchecked.
      int joined = 0;
      for (const Roadmap::Edge& e : rm.edges(v))
        if (!rm.dropped(e.to)) {
          ++joined;
          CHECK_FALSE(rm.knownInvalid(e.id));
        }
      CHECK(joined >= 10);
    }
    CHECK(dropped > 0);
    CHECK(dropped < rm.size() / 2);
  }
}

TEST_CASE("A robot whose straight motion is free takes it without a roadmap; a wall makes it build one") {
  Scenario s = openScenario(6);
  s.robots = {disc("free", 0.3, {1, 1, 0}, {5, 1, 0}), disc("walled", 0.3, {1, 4.5, 0}, {5, 4.5, 0})};
  // A wall across the second robot's straight line, with room to go round
  // it above and below.
  s.obstacles.push_back(Obstacle::makeBox({3, 4.5}, {0.2, 1.0}));
  RobotModels m(s);
  CollisionWorld world(s);
  RoadmapSet roadmaps(world, m.raw, 300, 10, 1);
  const Deadline deadline(10);

  auto free = individualPath(world, roadmaps, *m.raw[0], 0, deadline, 1);
  REQUIRE(free.has_value());
  CHECK(roadmaps.built() == 0);
  CHECK(roadmaps.buildSeconds() == 0);
  // Exactly the straight motion, one step per resolution unit.
  CHECK(free->size() == static_cast<std::size_t>(m.raw[0]->stepsBetween(s.robots[0].start.data(), s.robots[0].goal.data())) + 1);
  for (std::size_t t = 0; t < free->size(); ++t) CHECK(free->at(t)[1] == doctest::Approx(1.0));

  auto walled = individualPath(world, roadmaps, *m.raw[1], 1, deadline, 1);
  REQUIRE(walled.has_value());
  CHECK(roadmaps.built() == 1);
  CHECK(roadmaps.buildSeconds() > 0);
  // Round the wall: somewhere off the straight line, never in the wall.
  bool detours = false;
  for (std::size_t t = 0; t < walled->size(); ++t) {
    detours = detours || std::abs(walled->at(t)[1] - 4.5) > 0.5;
    CHECK(world.stateValid(*m.raw[1], walled->at(t)));
  }
  CHECK(detours);
}

TEST_CASE("A robot in a pocket behind a narrow door grows the roadmap around the pocket, not everywhere") {
  // A 1.6 x 1.6 room in the corner of a 20 x 20 square, its one door 0.8
  // wide opening on a passage that turns up along a wall: no straight
  // motion leads out, and a roadmap of 50 vertices has none that joins
  // the room to the rest.
  // Both ways round: the start in the room (its own part is the small
  // one), and the goal in it (the search from the goal finds the room).
  for (const bool start_inside : {true, false}) {
    CAPTURE(start_inside);
    Scenario s = openScenario(20);
    const std::vector<double> room{0.8, 0.8, 0}, out{15, 15, 0};
    s.robots = {disc("a", 0.3, start_inside ? room : out, start_inside ? out : room)};
    s.obstacles.push_back(Obstacle::makeBox({0.9, 1.7}, {1.8, 0.2}));   // top wall
    s.obstacles.push_back(Obstacle::makeBox({1.7, 0.25}, {0.2, 0.5}));  // right wall, below the door
    s.obstacles.push_back(Obstacle::makeBox({1.7, 1.5}, {0.2, 0.4}));   // and above it: door y in [0.5, 1.3]
    s.obstacles.push_back(Obstacle::makeBox({2.9, 1.3}, {0.2, 2.6}));   // the passage's far wall
    RobotModels m(s);
    CollisionWorld world(s);
    RoadmapSet roadmaps(world, m.raw, 50, 10, 1);
    Roadmap& rm = roadmaps.forRobot(0);
    {
      QueryGraph graph(rm, *m.raw[0]);
      const int a = graph.addVertex(s.robots[0].start.data(), 10), b = graph.addVertex(s.robots[0].goal.data(), 10);
      REQUIRE_FALSE(shortestPath(graph, a, b, Deadline()).has_value());  // the case this is about
    }
    auto path = individualPath(world, roadmaps, *m.raw[0], 0, Deadline(10), 1);
    REQUIRE(path.has_value());
    for (std::size_t t = 0; t < path->size(); ++t) CHECK(world.stateValid(*m.raw[0], path->at(t)));
    // Grown near the room only (doubling would have put most new
    // vertices all over the square), and by no more than doubling would.
    REQUIRE(rm.size() > 50);
    CHECK(rm.size() <= 50 + 3 * 64);
    int far = 0;
    for (int v = 50; v < rm.size(); ++v) far += rm.config(v)[0] > 6.0 || rm.config(v)[1] > 6.0;
    CHECK(far == 0);
  }
}

// Plans `model` from start to goal on `rm` among moving obstacles with
// the space-time search, and checks the path it returns instant by
// instant against their exact bodies. Tallies paths found, those that
// arrive later than the robot alone would, and searches that found none.
struct SearchTally {
  int found = 0, delayed = 0, none = 0;
};
void searchAmongMoving(Roadmap& rm, const RobotModel& model, const double* start, const double* goal,
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

TEST_CASE("A space-time search among crossing robots returns paths clear of them at every instant") {
  // A turning box robot on a roadmap, three box robots sweeping straight
  // across its square, turning as they go. The search meets the same edge
  // at many start times and in both directions (what it keeps of a motion
  // between tries must be that motion's, at the right instants); every
  // path it returns is checked here instant by instant.
  Scenario s = fourBoxes();
  RobotModels m(s);
  CollisionWorld world(s);
  const RobotModel& model = *m.raw[0];
  Roadmap rm(world, model, 10, 5);
  rm.grow(400);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> pos(0.5, 5.5), ang(-3.0, 3.0);
  const std::size_t horizon = 400;
  SearchTally tally;
  for (int trial = 0; trial < 150; ++trial) {
    std::vector<Path> sweeps;
    for (int i = 0; i < 3; ++i) {
      // From one side of the square to the other, 0.04 a step, turning.
      const double y0 = pos(rng), y1 = pos(rng), th0 = ang(rng), th1 = ang(rng);
      const bool across = trial % 2 == 0;
      Path p(3);
      const int steps = 60 + 40 * (trial % 3);
      for (int t = 0; t <= steps; ++t) {
        const double f = static_cast<double>(t) / steps, a = 0.3 + 5.4 * f, b = y0 + (y1 - y0) * f;
        const double q[3] = {across ? a : b, across ? b : a, th0 + (th1 - th0) * f};
        p.push(q);
      }
      sweeps.push_back(std::move(p));
    }
    std::vector<MovingObstacle> obstacles;
    for (int i = 0; i < 3; ++i) obstacles.push_back({m.raw[static_cast<std::size_t>(i) + 1], &sweeps[static_cast<std::size_t>(i)], 0, i + 1});
    const std::vector<double> start{pos(rng), pos(rng), ang(rng)}, goal{pos(rng), pos(rng), ang(rng)};
    if (!world.stateValid(model, start.data()) || !world.stateValid(model, goal.data())) continue;
    searchAmongMoving(rm, model, start.data(), goal.data(), obstacles, horizon, tally);
  }
  CHECK(tally.found > 100);
  CHECK(tally.none < 30);  // most crossings leave a way through
  CHECK(tally.delayed > 10);  // the crossings got in the way, and the search went around or waited
}

TEST_CASE("The space-time search keeps an arm clear of neighbouring arms that sweep their links past it") {
  // Arms' bounding discs, centred on their fixed bases, always meet their
  // neighbours', so the search's broad phase bounds the arms' bodies over
  // chunks of instants and over the part of each roadmap edge in a chunk
  // (edges here take many steps). Every path it returns is checked here
  // instant by instant against the neighbours' exact bodies.
  Scenario s = openScenario(9);
  s.robots.push_back(fiveLinkArm("mid", {4.5, 4.5}, 0.0, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}));
  s.robots.push_back(fiveLinkArm("left", {2.0, 4.5}, 0.0, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}));
  s.robots.push_back(fiveLinkArm("right", {7.0, 4.5}, 3.14159, {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}));
  RobotModels m(s);
  CollisionWorld world(s);
  const RobotModel& model = *m.raw[0];
  Roadmap rm(world, model, 10, 5);
  rm.grow(600);
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> joint(-2.0, 2.0);
  using Config = std::array<double, 5>;
  auto config = [&]() {
    Config q;
    for (double& v : q) v = joint(rng);
    return q;
  };
  const std::size_t horizon = 600;
  SearchTally tally;
  for (int trial = 0; trial < 60; ++trial) {
    // Each neighbour starts and ends stretched away from the middle arm
    // and reaches over to it through two random configurations on the
    // way, 0.15 rad a step at most per joint (fast enough that a chunk's
    // bounds taken from one of its instants miss collisions here).
    std::vector<Path> sweeps;
    const Config away{3.0, 0, 0, 0, 0};
    for (std::size_t r = 1; r <= 2; ++r) {
      Path p(5);
      Config q = away;
      for (int leg = 0; leg < 3; ++leg) {
        const Config to = leg == 2 ? away : config();
        double span = 0.0;
        for (std::size_t j = 0; j < 5; ++j) span = std::max(span, std::abs(to[j] - q[j]));
        const int steps = std::max(1, static_cast<int>(std::ceil(span / 0.15)));
        for (int t = 0; t < steps; ++t) {
          Config at;
          for (std::size_t j = 0; j < 5; ++j) at[j] = q[j] + (to[j] - q[j]) * t / steps;
          p.push(at.data());
        }
        q = to;
      }
      p.push(q.data());
      sweeps.push_back(std::move(p));
    }
    const std::vector<MovingObstacle> obstacles{{m.raw[1], &sweeps[0], 0, 1}, {m.raw[2], &sweeps[1], 0, 2}};
    const Config start = config(), goal = config();
    if (!world.stateValid(model, start.data()) || !world.stateValid(model, goal.data())) continue;
    CAPTURE(trial);
    searchAmongMoving(rm, model, start.data(), goal.data(), obstacles, horizon, tally);
  }
  CHECK(tally.found > 40);
  CHECK(tally.delayed > 8);  // the neighbours got in the way
}

TEST_CASE("The space-time search arrives as early with the roadmap-distance heuristic as with the straight line, and gives up exactly when the horizon is too short") {
  // A disc among walls that the straight line runs through, and a box
  // robot sweeping across. Both heuristics never overestimate, so A*
  // finds the earliest arrival with either; one step less of horizon
  // leaves none (the search stops once its least f passes the horizon).
  Scenario s = openScenario(8);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {7, 7, 0}), RobotSpec::mobileBox("b", {0.6, 0.4})};
  s.robots[1].start = s.robots[1].goal = {0, 0, 0};
  s.obstacles.push_back(Obstacle::makeBox({2.7, 3.0}, {0.3, 6.0}));  // open at the top
  s.obstacles.push_back(Obstacle::makeBox({5.3, 5.0}, {0.3, 6.0}));  // open at the bottom
  SearchWorld w(s, 500);
  const RobotModels& m = w.m;
  const CollisionWorld& world = w.world;
  const RobotModel& model = w.model();
  Roadmap& rm = w.rm;
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> pos(0.4, 7.6);
  int compared = 0, detours = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const double y0 = pos(rng), y1 = pos(rng);
    const Path sweep = line({0.4, y0, 0.0}, {7.6, y1, 3.0}, 151);  // left to right, turning
    const std::vector<MovingObstacle> obstacles{{m.raw[1], &sweep, 0, 1}};
    const std::vector<double> start{pos(rng), pos(rng), 0}, goal{pos(rng), pos(rng), 0};
    if (!world.stateValid(model, start.data()) || !world.stateValid(model, goal.data())) continue;
    QueryGraph graph(rm, model);
    const int sv = graph.addVertex(start.data(), 10), gv = graph.addVertex(goal.data(), 10);
    auto line = spaceTimeSearch(graph, sv, gv, obstacles, 600, 0, Deadline(), 2000000, false);
    auto roads = spaceTimeSearch(graph, sv, gv, obstacles, 600, 0, Deadline(), 2000000, true);
    REQUIRE(line.has_value() == roads.has_value());
    if (!line) continue;
    ++compared;
    CAPTURE(trial);
    CHECK(roads->size() == line->size());
    const std::size_t arrival = line->size() - 1;
    if (static_cast<double>(arrival) > 1.5 * model.distance(start.data(), goal.data()) + 2) ++detours;
    for (const bool by_roads : {false, true}) {
      CHECK(spaceTimeSearch(graph, sv, gv, obstacles, arrival, 0, Deadline(), 2000000, by_roads).has_value());
      CHECK_FALSE(spaceTimeSearch(graph, sv, gv, obstacles, arrival - 1, 0, Deadline(), 2000000, by_roads).has_value());
    }
  }
  CHECK(compared > 30);
  CHECK(detours > 5);  // the walls made many ways longer than the straight line
}

TEST_CASE("The searches over a roadmap count their work, so that a budget of work ends them as one of seconds would") {
  // A disc in an open square on a large roadmap. Its edges are checked by
  // a first search and cached, so that what the searches count after it
  // is their own queue work. The space-time search's distances to the
  // goal visit the whole roadmap (6,000 vertices), however near the goal.
  Scenario s = openScenario(8);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {2, 1, 0}), disc("b", 0.3, {6, 6, 0}, {6, 6, 0})};
  SearchWorld w(s, 6000);
  const RobotModels& m = w.m;
  const RobotModel& model = w.model();
  QueryGraph graph(w.rm, model);
  const double start[3] = {1, 1, 0}, goal[3] = {2.5, 1.5, 0};
  const int sv = graph.addVertex(start, 10), gv = graph.addVertex(goal, 10);
  REQUIRE(spaceTimeSearch(graph, sv, gv, {}, 200, 0, Deadline(), 1000000, true).has_value());  // checks the edges

  auto workOf = [&](auto&& search) {
    const std::uint64_t before = t_work_done;
    search();
    return t_work_done - before;
  };
  std::optional<std::vector<int>> vertices;
  const std::uint64_t shortest = workOf([&] { vertices = shortestPath(graph, sv, gv, Deadline()); });
  REQUIRE(vertices.has_value());
  CHECK(shortest >= kWorkPerGraphPop * vertices->size());
  const std::uint64_t by_line = workOf([&] { REQUIRE(spaceTimeSearch(graph, sv, gv, {}, 200, 0, Deadline(), 1000000, false)); });
  const std::uint64_t by_roads = workOf([&] { REQUIRE(spaceTimeSearch(graph, sv, gv, {}, 200, 0, Deadline(), 1000000, true)); });
  CHECK(by_roads >= by_line + kWorkPerGraphPop * 5000);

  // A budget of work halfway between the two: enough for the search by
  // the straight line, not for the one that first measures the roadmap.
  const double halfway = static_cast<double>(by_line + by_roads) / 2 / kWorkPerBudgetSecond;
  const Deadline budget = Deadline().withWorkBudgets(true);
  CHECK(spaceTimeSearch(graph, sv, gv, {}, 200, 0, budget.capped(halfway), 1000000, false).has_value());
  CHECK_FALSE(spaceTimeSearch(graph, sv, gv, {}, 200, 0, budget.capped(halfway), 1000000, true).has_value());
  CHECK(spaceTimeSearch(graph, sv, gv, {}, 200, 0, budget.capped(2 * halfway), 1000000, true).has_value());

  // A budget that ends in the search's own loop ends it at the expansion
  // that spends it (a few units each here), not expansions later. A
  // second disc parked on the goal for 100 steps makes the search expand
  // many states before the robot may arrive.
  Path parked(3);
  for (int t = 0; t <= 100; ++t) parked.push(goal);
  const double away[3] = {6, 6, 0};
  parked.push(away);
  const std::vector<MovingObstacle> obstacles{{m.raw[1], &parked, 0, 1}};
  const std::uint64_t waiting = workOf([&] { REQUIRE(spaceTimeSearch(graph, sv, gv, obstacles, 200, 150, Deadline(), 1000000, false)); });
  REQUIRE(waiting > 20000);
  const std::uint64_t units = waiting / 2;
  const std::uint64_t stopped = workOf([&] {
    CHECK_FALSE(spaceTimeSearch(graph, sv, gv, obstacles, 200, 150,
                                budget.capped(static_cast<double>(units) / kWorkPerBudgetSecond), 1000000, false)
                    .has_value());
  });
  CHECK(stopped >= units);
  CHECK(stopped <= units + 16);  // 2 over here; 67 when the loop read its budget every 256 expansions
}

TEST_CASE("Once nothing near it moves, a space-time search that finds no way stops searching later steps") {
  // A ring of resting discs walls the goal in. The roadmap knows nothing
  // of them (they are robots), so only the space-time search can find
  // that there is no way; once the world stands still, being at a vertex
  // later is no better than being there sooner, and a longer horizon
  // should cost next to nothing more.
  Scenario s = openScenario(8);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {5, 5, 0})};
  const std::vector<double> goal{5, 5, 0};
  std::vector<Path> ring;
  for (int j = 0; j < 8; ++j) {
    const double angle = j * test::kPi / 4;
    const std::vector<double> q{5 + 0.65 * std::cos(angle), 5 + 0.65 * std::sin(angle), 0};
    s.robots.push_back(disc("r" + std::to_string(j), 0.3, q, q));
    ring.push_back(line({q}));
  }
  SearchWorld w(s, 1500);
  const RobotModels& m = w.m;
  QueryGraph graph(w.rm, w.model());
  const double start[3] = {1, 1, 0};
  const int sv = graph.addVertex(start, 10), gv = graph.addVertex(goal.data(), 10);
  std::vector<MovingObstacle> obstacles;
  for (int j = 0; j < 8; ++j) obstacles.push_back({m.raw[static_cast<std::size_t>(j + 1)], &ring[static_cast<std::size_t>(j)], 0, j + 1});
  REQUIRE(spaceTimeSearch(graph, sv, gv, {}, 1000, 0, Deadline(), 10000000).has_value());
  auto workOf = [&](std::size_t horizon) {
    const std::uint64_t before = t_work_done;
    SearchEnd end = SearchEnd::Found;
    CHECK_FALSE(spaceTimeSearch(graph, sv, gv, obstacles, horizon, 0, Deadline(), 10000000, false, &end));
    CHECK(end == SearchEnd::NoWay);
    return t_work_done - before;
  };
  workOf(300);  // checks the edges it reaches, so that what is counted next is the searches' own work
  const std::uint64_t short_horizon = workOf(300), long_horizon = workOf(1200);
  CAPTURE(short_horizon);
  CAPTURE(long_horizon);
  CHECK(long_horizon < short_horizon * 5 / 4);  // searching every vertex at every step: 8 times
}

TEST_CASE("A roadmap whose deadline has passed grows no further and checks no edge") {
  Scenario s = openScenario(6);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {5, 5, 0})};
  RobotModels m(s);
  CollisionWorld world(s);
  const double start[3] = {1, 1, 0}, goal[3] = {2, 1, 0};
  // In time: the query's start and goal, joined directly, make a path.
  Roadmap rm(world, *m.raw[0], 10, 3, Deadline(1e6));
  QueryGraph in_time(rm, *m.raw[0]);
  const int s0 = in_time.addVertex(start, 10), g0 = in_time.addVertex(goal, 10);
  CHECK(shortestPath(in_time, s0, g0, Deadline()).has_value());
  // Late: no vertex, and the same edge reads as invalid without being
  // marked so (it was never checked), and the search gives up even with
  // time of its own left.
  Roadmap late(world, *m.raw[0], 10, 3, Deadline(-1.0));
  late.grow(300);
  CHECK(late.size() == 0);
  QueryGraph graph(late, *m.raw[0]);
  const int s1 = graph.addVertex(start, 10), g1 = graph.addVertex(goal, 10);
  int key = 0;
  graph.forEachEdge(s1, [&](int to, int, int k) {
    if (to == g1) key = k;
  });
  REQUIRE(key < 0);  // a query edge
  CHECK_FALSE(graph.edgeValid(key));
  CHECK_FALSE(graph.knownInvalid(key));
  CHECK_FALSE(shortestPath(graph, s1, g1, Deadline()).has_value());
}

TEST_CASE("A roadmap joins each vertex to its nearest once: one edge per pair, listed at both ends") {
  Scenario s = openScenario(6);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {5, 5, 0})};
  RobotModels m(s);
  CollisionWorld world(s);
  Roadmap rm(world, *m.raw[0], 10, 3);
  // A vertex is joined to each of its 10 nearest other vertices as they
  // were when it was added.
  auto joinedToNearest = [&](int from) {
    for (int v = from; v < rm.size(); v += 7) {
      std::set<int> adjacent;
      for (const Roadmap::Edge& e : rm.edges(v)) adjacent.insert(e.to);
      for (int u : rm.nearest(rm.config(v), 11))
        if (u != v) CHECK(adjacent.count(u));
    }
  };
  rm.grow(300);
  joinedToNearest(0);
  rm.grow(100);  // vertices added later join the older ones too
  joinedToNearest(300);
  REQUIRE(rm.size() == 400);
  std::map<int, std::vector<std::pair<int, int>>> ends_of;  // edge id -> (from, to) as listed
  for (int v = 0; v < rm.size(); ++v) {
    std::set<int> seen;
    for (const Roadmap::Edge& e : rm.edges(v)) {
      CHECK(e.to != v);
      CHECK(seen.insert(e.to).second);  // no pair twice
      ends_of[e.id].emplace_back(v, e.to);
    }
  }
  for (const auto& [id, ends] : ends_of) {
    CAPTURE(id);
    REQUIRE(ends.size() == 2);
    CHECK(ends[0].first == ends[1].second);
    CHECK(ends[0].second == ends[1].first);
  }
}

TEST_CASE("A point index answers into the caller's buffers what it returns afresh") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-3, 3);
  PointIndex index(3);
  for (int i = 0; i < 200; ++i) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    index.add(p);
  }
  // One pair of buffers for every query, the k going up and down, so a
  // longer earlier answer must not leak into a shorter later one.
  std::vector<std::size_t> idx;
  std::vector<double> d2;
  for (std::size_t k : {15u, 3u, 0u, 500u, 1u, 11u}) {
    CAPTURE(k);
    const double q[3] = {u(rng), u(rng), u(rng)};
    index.nearest(q, k, idx, d2);
    CHECK(idx == index.nearest(q, k));
    CHECK(idx.size() == std::min<std::size_t>(k, 200));
  }
}

TEST_CASE("Every method reports a solution as solved only when it validates") {
  Scenario s = openScenario(6);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {5, 5, 0}), disc("b", 0.3, {5, 5, 0}, {1, 1, 0})};
  for (Method m : {Method::Arc, Method::Prioritized, Method::Coupled}) {
    CAPTURE(methodName(m));
    PlannerSettings settings;
    settings.method = m;
    settings.time_limit_s = 20;
    PlanResult r = plan(s, settings);
    REQUIRE(r.solution.solved);
    CHECK(validateSolution(s, r.solution).valid);
    CHECK(r.solution.method == methodName(m));
  }
}

TEST_CASE("A solution's paths end where each robot last moves, so sum of costs is not n x makespan") {
  // The prioritized baseline padded every path to the makespan: a robot
  // with a short trip was charged for waiting at its goal.
  Scenario s = openScenario(8);
  s.robots = {disc("near", 0.3, {1, 1, 0}, {2, 1, 0}), disc("far", 0.3, {1, 3, 0}, {7, 7, 0})};
  for (Method m : {Method::Arc, Method::Prioritized, Method::Coupled}) {
    CAPTURE(std::string(methodName(m)));
    PlannerSettings settings;
    settings.method = m;
    settings.time_limit_s = 20;
    PlanResult r = plan(s, settings);
    REQUIRE(r.solution.solved);
    for (const Path& p : r.solution.paths) {
      REQUIRE(p.size() >= 2);
      CHECK_FALSE(std::equal(p.at(p.size() - 1), p.at(p.size() - 1) + p.dim(), p.at(p.size() - 2)));
    }
    // Coupled planning moves every robot along each composite edge, so
    // the near robot creeps until the end; the others plan each robot alone.
    if (m == Method::Coupled) continue;
    CHECK(r.solution.paths[0].size() < r.solution.paths[1].size());
    CHECK(r.stats["sum_of_costs"].get<std::size_t>() < 2 * r.stats["makespan"].get<std::size_t>());
  }
}

TEST_CASE("Dropping a path's trailing waits keeps every state up to its last move") {
  Path p = line({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 0, 0}, {2, 0, 0}});
  p.dropTrailingWaits();
  CHECK(p == line({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 0, 0}}));
  Path still = line({{3, 3, 1}, {3, 3, 1}});
  still.dropTrailingWaits();
  CHECK(still == line({{3, 3, 1}}));
  Path turn = line({{3, 3, 1}, {3, 3, 1.5}});
  turn.dropTrailingWaits();
  CHECK(turn.size() == 2);
}
