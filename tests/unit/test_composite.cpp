// The composite space of several robots: the validity check (with its
// broad phase for many robots), its deadline, and the flat OMPL space
// against the compound of per-robot OMPL spaces whose metric it keeps;
// polishing and retiming a composite path.
#include <doctest/doctest.h>

#include <ompl/base/ScopedState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>

#include <numbers>
#include <random>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/composite.hpp"
#include "earc/planning/coupled_solver.hpp"
#include "earc/planning/ompl_composite.hpp"
#include "earc/planning/roadmap.hpp"
#include "earc/scene/robot_model.hpp"

using namespace earc;
namespace ob = ompl::base;

namespace {

RobotSpec arm(const std::string& name, geo::Vec2 base) {
  RobotSpec s;
  s.name = name;
  s.kind = RobotKind::Manipulator;
  s.base_position = base;
  s.links = {0.5, 0.5, 0.5};
  s.link_radius = 0.05;
  s.joint_limits = {{-3.0, 3.0}, {-2.6, 2.6}, {-2.6, 2.6}};
  s.start = s.goal = {0, 0, 0};
  return s;
}

// n mobile robots, discs and boxes alternating, in a size x size workspace.
Scenario crowd(int n, double size = 10) {
  Scenario s;
  s.name = "crowd";
  s.workspace = {{0, 0}, {size, size}};
  for (int i = 0; i < n; ++i) {
    RobotSpec r = i % 2 ? RobotSpec::mobileBox("b" + std::to_string(i), {0.6, 0.4}) : RobotSpec{};
    if (i % 2 == 0) {
      r.name = "d" + std::to_string(i);
      r.kind = RobotKind::Mobile;
      r.shape = MobileShape::Disc;
      r.radius = 0.3;
    }
    r.start = r.goal = {1, 1, 0};
    s.robots.push_back(r);
  }
  return s;
}


}  // namespace

TEST_CASE("The composite validity check with its broad phase agrees with testing every pair") {
  const int n = 40;
  const double size = 40;
  Scenario s = crowd(n, size);
  RobotModels m(s);
  CollisionWorld world(s);
  CompositeChecker checker(world, m.raw);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> xy(-1.0, 1.0), th(-3.14, 3.14);
  int valid = 0, invalid = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // Spread the robots over squares of different sizes: from mostly clear
    // to mostly touching.
    const double half = (size / 2 - 0.6) * (0.1 + 0.9 * (trial % 20) / 19.0);
    CompositeState q(n);
    for (auto& c : q) c = {size / 2 + xy(rng) * half, size / 2 + xy(rng) * half, th(rng)};
    bool expect = true;
    for (int i = 0; i < n && expect; ++i)
      for (int j = i + 1; j < n; ++j)
        if (robotsTouch(*m.raw[i], q[i].data(), *m.raw[j], q[j].data())) {
          expect = false;
          break;
        }
    CHECK(checker.stateValid(q) == expect);
    (expect ? valid : invalid) += 1;
  }
  // Both answers were exercised.
  CHECK(valid > 20);
  CHECK(invalid > 20);
}

TEST_CASE("The composite validity check among obstacles agrees with checking each robot, then each pair") {
  // Few robots (every pair tested) and many (the sweep), each robot's
  // bodies placed once for the obstacles and its neighbours.
  for (const int n : {4, 10}) {
    const double size = 2.0 * n;
    Scenario s = crowd(n, size);
    s.robots.push_back(arm("arm", {size / 2, size / 2}));
    std::mt19937_64 rng(static_cast<unsigned>(n));
    std::uniform_real_distribution<double> xy(0.2, size - 0.2), th(-3.0, 3.0);
    for (int i = 0; i < 6; ++i) s.obstacles.push_back(Obstacle::makeBox({xy(rng), xy(rng)}, {0.8, 0.5}, th(rng)));
    RobotModels m(s);
    CollisionWorld world(s);
    CompositeChecker checker(world, m.raw);
    int valid = 0, invalid = 0, by_obstacle = 0;
    for (int trial = 0; trial < 600; ++trial) {
      CompositeState q;
      for (const RobotModel* r : m.raw)
        q.push_back(r->isMobile() ? std::vector<double>{xy(rng), xy(rng), th(rng)}
                                  : std::vector<double>{th(rng), th(rng) * 0.8, th(rng) * 0.8});
      bool expect = true;
      for (std::size_t i = 0; i < q.size() && expect; ++i)
        if (!world.stateValid(*m.raw[i], q[i].data())) expect = false, ++by_obstacle;
      for (std::size_t i = 0; i < q.size() && expect; ++i)
        for (std::size_t j = i + 1; j < q.size() && expect; ++j)
          if (robotsTouch(*m.raw[i], q[i].data(), *m.raw[j], q[j].data())) expect = false;
      CHECK(checker.stateValid(q) == expect);
      (expect ? valid : invalid) += 1;
    }
    CHECK(valid > 20);
    CHECK(invalid - by_obstacle > 20);  // some states fail only on a pair of robots
  }
}

TEST_CASE("One robot's part of a motion decides it when the others' part is valid") {
  // Three box robots apart from each other and from the obstacle, and a
  // fourth anywhere: the full check and the one robot's check must agree.
  Scenario s = crowd(4, 10);
  for (auto& r : s.robots) r = RobotSpec::mobileBox(r.name, {0.6, 0.4}), r.start = r.goal = {1, 1, 0};
  // The same robots with nothing around them: the answer when robot r's
  // own motion is known valid against the world.
  Scenario open = s;
  open.workspace = {{-100, -100}, {100, 100}};
  s.obstacles.push_back(Obstacle::makeBox({5, 2}, {1.5, 0.8}, 0.3));
  RobotModels m(s);
  CollisionWorld world(s), nothing(open);
  CompositeChecker checker(world, m.raw), among_robots(nothing, m.raw);
  int start_known = 0, world_known = 0;
  const double step = m.raw[0]->resolution().translation;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> xy(0.0, 10.0), th(-3.0, 3.0), jitter(-0.7, 0.7);
  const std::vector<std::vector<double>> parked{{2.5, 7.5, 0.0}, {7.5, 7.5, 1.0}, {7.5, 4.5, 2.0}};
  int valid = 0, invalid = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const std::size_t r = static_cast<std::size_t>(trial) % 4;
    CompositeState a(4), b(4);
    for (std::size_t w = 0, k = 0; w < 4; ++w) {
      if (w == r) {
        a[w] = {xy(rng), xy(rng), th(rng)};
      } else {
        a[w] = parked[k++];
        a[w][0] += jitter(rng), a[w][1] += jitter(rng);
      }
      // At most one step of translation, as in a time-stamped path; some still.
      const bool still = trial % 5 == 0 && w != r;
      b[w] = {a[w][0] + (still ? 0 : jitter(rng) * step), a[w][1] + (still ? 0 : jitter(rng) * step), a[w][2]};
    }
    std::vector<const double*> pa, pb;
    for (std::size_t w = 0; w < 4; ++w) pa.push_back(a[w].data()), pb.push_back(b[w].data());
    const bool full = checker.motionValid(a, b);
    CHECK(checker.robotMotionValid(r, pa, pb) == full);
    (full ? valid : invalid) += 1;
    // Told that the first state is valid, it checks only the rest; told
    // that robot r is clear of the world, only the other robots.
    if (checker.stateValid(a)) {
      CHECK(checker.robotMotionValid(r, pa, pb, {.start = true}) == full);
      ++start_known;
    }
    if (among_robots.stateValid(a) && among_robots.motionValid(a, b) != full) {
      CHECK(checker.robotMotionValid(r, pa, pb, {.world = true}));  // invalid only against the world
      ++world_known;
    }
    CHECK(checker.robotMotionValid(r, pa, pb, {.world = true}) == among_robots.motionValid(a, b));
  }
  CHECK(valid > 200);
  CHECK(invalid > 200);
  CHECK(start_known > 200);
  CHECK(world_known > 100);
}

TEST_CASE("A step checked against the other robots' bodies placed once agrees with placing them each time") {
  // Three arms side by side, close enough to reach into each other,
  // wandering through random one-step paths; then robot 0's path changes
  // from step 20 on and the bodies kept for it are forgotten from there.
  Scenario s;
  s.name = "row";
  s.workspace = {{-3, -3}, {6, 3}};
  s.robots = {arm("a", {0, 0}), arm("b", {1.2, 0}), arm("c", {2.4, 0})};
  RobotModels m(s);
  CollisionWorld world(s);
  CompositeChecker checker(world, m.raw);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> joint(-2.5, 2.5);
  auto wander = [&](const RobotModel& model, std::size_t legs) {
    std::vector<std::vector<double>> way;
    for (std::size_t i = 0; i <= legs; ++i) way.push_back({joint(rng), joint(rng), joint(rng)});
    return timeStamp(model, way);
  };
  std::vector<Path> paths;
  for (const RobotModel* model : m.raw) paths.push_back(wander(*model, 4));
  // `along` is told of the change; `stale` is not, and shows that the
  // change matters to the answers.
  BodiesAlongPaths along(m.raw, paths), stale(m.raw, paths);
  struct Tally {
    int blocked = 0, stale_differs = 0;
  };
  auto agree = [&]() {
    Tally tally;
    std::size_t last = 0;
    for (const auto& p : paths) last = std::max(last, p.size() - 1);
    std::vector<const double*> from(3), to(3);
    for (int pass = 0; pass < 2; ++pass)  // the second pass reads what the first placed
      for (std::size_t t = 0; t < last; ++t)
        for (std::size_t r = 0; r < 3; ++r) {
          for (std::size_t w = 0; w < 3; ++w) from[w] = paths[w].at(t), to[w] = paths[w].at(t + 1);
          for (KnownValid known : {KnownValid{.start = true}, KnownValid{.start = true, .world = true}}) {
            const bool placed_each_time = checker.robotMotionValid(r, from, to, known);
            CHECK(checker.robotStepValid(r, from, to, known, along, t) == placed_each_time);
            tally.stale_differs += checker.robotStepValid(r, from, to, known, stale, t) != placed_each_time;
            tally.blocked += !placed_each_time;
          }
        }
    return tally;
  };
  const Tally before = agree();
  CHECK(before.blocked > 100);  // the arms reach into each other often
  CHECK(before.stale_differs == 0);
  // Robot 0 takes another way from step 20 on.
  REQUIRE(paths[0].size() > 40);
  Path changed = paths[0].slice(0, 21);
  const Path detour = wander(*m.raw[0], 3);
  std::vector<std::vector<double>> bridge{std::vector<double>(changed.back(), changed.back() + 3),
                                          std::vector<double>(detour.at(0), detour.at(0) + 3)};
  changed.append(timeStamp(*m.raw[0], bridge), 1);
  changed.append(detour, 1);
  paths[0] = changed;
  along.forget(0, 20);
  const Tally after = agree();
  CHECK(after.blocked > 100);
  CHECK(after.stale_differs > 10);
}

TEST_CASE("A composite motion between states known to be valid is decided by the instants between") {
  // Two discs and a box obstacle; motions of a few steps between random
  // states. When both ends are valid, leaving them out changes nothing;
  // when an end is invalid, it is exactly what the caller vouched for.
  Scenario s = crowd(2, 6);
  s.obstacles.push_back(Obstacle::makeBox({3, 3}, {1.2, 0.6}, 0.4));
  RobotModels m(s);
  CollisionWorld world(s);
  CompositeChecker checker(world, m.raw);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> xy(0.4, 5.6), jitter(-1.5, 1.5);
  int both_valid = 0, blocked_between = 0, end_invalid = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    CompositeState a(2), b(2);
    for (std::size_t r = 0; r < 2; ++r) {
      a[r] = {xy(rng), xy(rng), 0.0};
      b[r] = {a[r][0] + jitter(rng), a[r][1] + jitter(rng), 0.0};
    }
    const bool a_ok = checker.stateValid(a), b_ok = checker.stateValid(b);
    const bool full = checker.motionValid(a, b);
    const KnownValid ends{.start = true, .end = true};
    if (a_ok && b_ok) {
      ++both_valid;
      CHECK(checker.motionValid(a, b, ends) == full);
      CHECK(checker.lastValidFraction(a, b, ends) == checker.lastValidFraction(a, b));
      CHECK(checker.motionValid(a, b, {.start = true}) == full);
      CHECK(checker.motionValid(a, b, {.end = true}) == full);
      if (!full) ++blocked_between;
    } else if (a_ok && !b_ok && compositeSteps(m.raw, a, b) > 0) {
      ++end_invalid;
      CHECK_FALSE(full);
      CHECK_FALSE(checker.motionValid(a, b, {.start = true}));  // the end is still checked
    }
  }
  CHECK(both_valid > 500);
  CHECK(blocked_between > 20);  // valid ends, a collision on the way
  CHECK(end_invalid > 50);
}

TEST_CASE("A motion check's yes or no, and where a motion first fails, agree with testing every instant in order") {
  // Two discs and two obstacles, motions of up to a few dozen steps. The
  // yes-or-no check stops at the first collision it finds (coarse to
  // fine); where the motion first fails is the earliest instant.
  Scenario s = crowd(2, 8);
  s.obstacles.push_back(Obstacle::makeBox({3, 4}, {0.4, 3.0}, 0.2));
  s.obstacles.push_back(Obstacle::makeBox({5.5, 2.5}, {1.5, 0.4}));
  RobotModels m(s);
  CollisionWorld world(s);
  CompositeChecker checker(world, m.raw);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> xy(0.4, 7.6), heading(-3.0, 3.0);
  int valid = 0, invalid = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    CompositeState a(2), b(2);
    for (std::size_t r = 0; r < 2; ++r) {
      a[r] = {xy(rng), xy(rng), heading(rng)};
      b[r] = {xy(rng), xy(rng), heading(rng)};
    }
    const int n = compositeSteps(m.raw, a, b);
    REQUIRE(n > 0);
    int first_bad = -1;
    CompositeState q(2);
    for (int k = 0; k <= 2 * n && first_bad < 0; ++k) {
      for (std::size_t r = 0; r < 2; ++r) {
        q[r].resize(3);
        m.raw[r]->interpolate(a[r].data(), b[r].data(), static_cast<double>(k) / (2 * n), q[r].data());
      }
      if (!checker.stateValid(q)) first_bad = k;
    }
    CAPTURE(trial);
    CHECK(checker.motionValid(a, b) == (first_bad < 0));
    const double expected = first_bad < 0 ? 1.0 : std::max(0.0, static_cast<double>(first_bad - 1) / (2 * n));
    CHECK(checker.lastValidFraction(a, b) == doctest::Approx(expected));
    (first_bad < 0 ? valid : invalid)++;
  }
  CHECK(valid > 50);
  CHECK(invalid > 500);
}

TEST_CASE("Shortcutting a path's ends goes straight to the furthest waypoint tried that the start reaches, and from it to the goal") {
  // One disc; a wall x in [4.5, 5.5], y in [0, 6]. The path backs away
  // from its start, climbs over the wall and comes down to a goal right of it.
  Scenario s = crowd(1, 10);
  s.obstacles.push_back(Obstacle::makeBox({5, 3}, {1, 6}));
  RobotModels m(s);
  CollisionWorld world(s);
  CompositeChecker checker(world, m.raw);
  auto at = [](double x, double y) { return CompositeState{{x, y, 0.0}}; };
  const std::vector<CompositeState> path{at(2, 2), at(1, 2), at(1, 5), at(2, 8), at(4, 8), at(5, 8),
                                         at(6, 8), at(8, 8),  at(9, 5), at(9, 2), at(8, 2)};
  for (std::size_t w = 1; w < path.size(); ++w) REQUIRE(checker.motionValid(path[w - 1], path[w]));
  // Tried from the start: the goal (10), then 7 (blocked by the wall),
  // then 5, over it. From the goal: 6 of the 7 left, then 4 (waypoint 6).
  REQUIRE_FALSE(checker.motionValid(path[0], path[10]));
  REQUIRE_FALSE(checker.motionValid(path[0], path[7]));
  REQUIRE(checker.motionValid(path[0], path[5]));
  REQUIRE(checker.motionValid(path[6], path[10]));

  std::vector<CompositeState> way = path;
  CHECK(shortcutEnds(checker, way) == 7);
  CHECK(way == std::vector<CompositeState>{path[0], path[5], path[6], path[10]});
  for (std::size_t w = 1; w < way.size(); ++w) CHECK(checker.motionValid(way[w - 1], way[w]));

  // Nothing in the way: start to goal in one motion.
  std::vector<CompositeState> open{at(2, 8), at(1, 9), at(3, 9.5), at(4, 8), at(8, 8.5)};
  CHECK(shortcutEnds(checker, open) == 3);
  CHECK(open == std::vector<CompositeState>{at(2, 8), at(8, 8.5)});

  // Round the wall tightly: no waypoint can be skipped.
  std::vector<CompositeState> tight{at(3, 2), at(3.5, 7), at(6.5, 7), at(7, 2)};
  std::vector<CompositeState> kept = tight;
  CHECK(shortcutEnds(checker, kept) == 0);
  CHECK(kept == tight);
}

TEST_CASE("A composite motion checked after the checker's deadline reads as invalid") {
  Scenario s = crowd(2);
  RobotModels m(s);
  CollisionWorld world(s);
  const CompositeState a = {{2, 2, 0}, {6, 6, 0}}, b = {{3, 2, 0}, {7, 6, 0}};
  CompositeChecker unlimited(world, m.raw);
  CHECK(unlimited.motionValid(a, b));
  const Deadline later(1e6);
  CHECK(CompositeChecker(world, m.raw, later).motionValid(a, b));
  const Deadline past(-1.0);
  CompositeChecker late(world, m.raw, past);
  CHECK_FALSE(late.motionValid(a, b));
  CHECK(late.lastValidFraction(a, b) == 0.0);
  // States too (OMPL's simplifier samples states after its time is up),
  // and a motion of one robot among others.
  CHECK(unlimited.stateValid(a));
  CHECK_FALSE(late.stateValid(a));
  CHECK(late.outOfTime());
  const std::vector<const double*> from{a[0].data(), a[1].data()}, to{b[0].data(), b[1].data()};
  CHECK(unlimited.robotMotionValid(0, from, to));
  CHECK_FALSE(late.robotMotionValid(0, from, to));
}

TEST_CASE("The flat composite space measures and interpolates exactly as a compound of SE2 and joint spaces") {
  // Two mobile robots around an arm: the layout the compound would have
  // had as SE2, RealVector(3), SE2.
  Scenario s = crowd(2);
  s.robots.insert(s.robots.begin() + 1, arm("a", {5, 5}));
  RobotModels m(s);
  CollisionWorld world(s);
  CompositeChecker checker(world, m.raw);
  std::vector<ConfigBox> bounds = {{{0.5, 1.0, -std::numbers::pi}, {9.0, 8.0, std::numbers::pi}},
                                   {{-3.0, -2.6, -2.6}, {3.0, 2.6, 2.6}},
                                   {{2.0, 0.5, -std::numbers::pi}, {7.5, 9.5, std::numbers::pi}}};
  OmplComposite flat(checker, bounds);

  auto compound = std::make_shared<ob::CompoundStateSpace>();
  for (const ConfigBox& b : bounds) {
    if (b.lo.size() == 3 && b.lo[2] == -std::numbers::pi) {
      auto se2 = std::make_shared<ob::SE2StateSpace>();
      ob::RealVectorBounds box(2);
      for (unsigned j = 0; j < 2; ++j) box.setLow(j, b.lo[j]), box.setHigh(j, b.hi[j]);
      se2->setBounds(box);
      compound->addSubspace(se2, 1.0);
    } else {
      auto rv = std::make_shared<ob::RealVectorStateSpace>(3);
      ob::RealVectorBounds box(3);
      for (unsigned j = 0; j < 3; ++j) box.setLow(j, b.lo[j]), box.setHigh(j, b.hi[j]);
      rv->setBounds(box);
      compound->addSubspace(rv, 1.0);
    }
  }
  compound->lock();
  auto toCompound = [&](const CompositeState& q, ob::State* st) {
    auto* cs = st->as<ob::CompoundState>();
    for (unsigned r : {0u, 2u}) {
      auto* se2 = cs->as<ob::SE2StateSpace::StateType>(r);
      se2->setXY(q[r][0], q[r][1]);
      se2->setYaw(geo::wrapAngle(q[r][2]));
    }
    std::copy(q[1].begin(), q[1].end(), cs->as<ob::RealVectorStateSpace::StateType>(1)->values);
  };
  auto fromCompound = [&](const ob::State* st) {
    const auto* cs = st->as<ob::CompoundState>();
    CompositeState q(3);
    for (unsigned r : {0u, 2u}) {
      const auto* se2 = cs->as<ob::SE2StateSpace::StateType>(r);
      q[r] = {se2->getX(), se2->getY(), se2->getYaw()};
    }
    const double* v = cs->as<ob::RealVectorStateSpace::StateType>(1)->values;
    q[1].assign(v, v + 3);
    return q;
  };

  CHECK(flat.space()->getMaximumExtent() == compound->getMaximumExtent());
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto sample = [&] {
    CompositeState q(3);
    for (std::size_t r = 0; r < 3; ++r)
      for (std::size_t j = 0; j < 3; ++j) q[r].push_back(bounds[r].lo[j] + u(rng) * (bounds[r].hi[j] - bounds[r].lo[j]));
    return q;
  };
  ob::ScopedState<> fa(flat.space()), fb(flat.space()), fm(flat.space());
  ob::ScopedState<> ca(compound), cb(compound), cm(compound);
  CompositeState got;
  for (int i = 0; i < 500; ++i) {
    const CompositeState a = sample(), b = sample();
    flat.fromComposite(a, fa.get());
    flat.fromComposite(b, fb.get());
    toCompound(a, ca.get());
    toCompound(b, cb.get());
    // Bit for bit, so that planners take exactly the steps they took on the
    // compound space.
    REQUIRE(flat.space()->distance(fa.get(), fb.get()) == compound->distance(ca.get(), cb.get()));
    const double t = u(rng);
    flat.space()->interpolate(fa.get(), fb.get(), t, fm.get());
    compound->interpolate(ca.get(), cb.get(), t, cm.get());
    flat.toComposite(fm.get(), got);
    REQUIRE(got == fromCompound(cm.get()));
  }
}

TEST_CASE("Polishing a path turns box robots steadily and makes it shorter, valid, with its ends kept") {
  // Two boxes pass a wall on opposite sides; RRT-Connect's waypoints carry
  // random headings, here a quarter turn back and forth at every one.
  Scenario s;
  s.name = "wall";
  s.workspace = {{0, 0}, {10, 10}};
  s.obstacles.push_back(Obstacle::makeBox({5, 5}, {1, 4}));
  s.robots = {RobotSpec::mobileBox("a", {0.6, 0.4}), RobotSpec::mobileBox("b", {0.6, 0.4})};
  s.robots[0].start = {1, 5, 0};
  s.robots[0].goal = {9, 5, 0.4};
  s.robots[1].start = {9, 4, 3.1};
  s.robots[1].goal = {1, 4, 3.1};
  const CollisionWorld world(s);
  const RobotModels models(s);
  const std::vector<const RobotModel*>& robots = models.raw;
  const CompositeChecker checker(world, robots);
  REQUIRE_FALSE(checker.motionValid({s.robots[0].start, s.robots[1].start}, {s.robots[0].goal, s.robots[1].goal}));
  // a: over the wall (y = 8), b: under it (y = 1), in steps of 0.5.
  std::vector<CompositeState> waypoints;
  const int n = 33;
  for (int w = 0; w < n; ++w) {
    const double f = static_cast<double>(w) / (n - 1);
    const double lift = std::sin(f * std::numbers::pi);
    const double zig = w % 2 ? std::numbers::pi / 2 : 0.0;
    waypoints.push_back({{1 + 8 * f, 5 + 3 * lift, zig}, {9 - 8 * f, 4 - 3 * lift, 3.1 + zig}});
  }
  waypoints.front() = {s.robots[0].start, s.robots[1].start};
  waypoints.back() = {s.robots[0].goal, s.robots[1].goal};
  for (std::size_t w = 1; w < waypoints.size(); ++w) REQUIRE(checker.motionValid(waypoints[w - 1], waypoints[w]));
  const std::size_t before = timeStampComposite(robots, waypoints).length();

  std::vector<CompositeState> polished = waypoints;
  std::mt19937_64 rng(7);
  polishComposite(checker, polished, rng, Deadline());
  const LocalSolution after = timeStampComposite(robots, polished);
  CHECK(after.length() < before);
  CHECK(polished.front() == waypoints.front());
  CHECK(polished.back() == waypoints.back());
  for (std::size_t w = 1; w < polished.size(); ++w) CHECK(checker.motionValid(polished[w - 1], polished[w]));
  // Steady turns: a's heading moves from 0 to 0.4 and never back; b keeps 3.1.
  double last = 0.0;
  for (std::size_t t = 0; t < after.length(); ++t) {
    const double h = after.paths[0].at(t)[2];
    CHECK(h >= last - 1e-9);
    CHECK(h <= 0.4 + 1e-9);
    last = h;
    CHECK(after.paths[1].at(t)[2] == doctest::Approx(3.1));
  }
}

TEST_CASE("Retiming lets each robot arrive as early as the others allow, one step at a time, and stays valid") {
  // a crosses the vertical line x = 5 at full speed, reaching it at step 80.
  // b waits below the crossing for 100 steps, then goes up at full speed:
  // it can set off earlier, but not straight away, or it meets a there.
  Scenario s;
  s.name = "crossing";
  s.workspace = {{0, 0}, {10, 10}};
  s.robots = {RobotSpec::mobileDisc("a", 0.3), RobotSpec::mobileDisc("b", 0.3)};
  s.robots[0].start = {1, 5, 0};
  s.robots[0].goal = {9, 5, 0};
  s.robots[1].start = {5, 1, 0};
  s.robots[1].goal = {5, 9, 0};
  const CollisionWorld world(s);
  const RobotModels models(s);
  const std::vector<const RobotModel*>& robots = models.raw;
  const CompositeChecker checker(world, robots);
  const int straight = robots[0]->stepsBetween(s.robots[0].start.data(), s.robots[0].goal.data());
  REQUIRE(straight == 160);
  std::vector<Path> paths{Path(3), Path(3)};
  std::vector<double> q(3);
  for (int t = 0; t <= straight; ++t) {
    robots[0]->interpolate(s.robots[0].start.data(), s.robots[0].goal.data(), static_cast<double>(t) / straight,
                           q.data());
    paths[0].push(q.data());
  }
  for (int t = 0; t < 100; ++t) paths[1].push(s.robots[1].start.data());
  for (int t = 0; t <= straight; ++t) {
    robots[1]->interpolate(s.robots[1].start.data(), s.robots[1].goal.data(), static_cast<double>(t) / straight,
                           q.data());
    paths[1].push(q.data());
  }
  auto stepsValid = [&](const std::vector<Path>& p) {
    std::size_t last = std::max(p[0].size(), p[1].size()) - 1;
    for (std::size_t t = 0; t < last; ++t) {
      const CompositeState a = stateAt(p, t), b = stateAt(p, t + 1);
      for (std::size_t r = 0; r < 2; ++r)
        if (robots[r]->stepsBetween(a[r].data(), b[r].data()) > 1) return false;
      if (!checker.motionValid(a, b)) return false;
    }
    return true;
  };
  REQUIRE(stepsValid(paths));
  const std::vector<Path> before = paths;

  std::mt19937_64 rng(3);
  retimeShortcut(checker, paths, 300, rng);
  CHECK(stepsValid(paths));
  for (std::size_t r = 0; r < 2; ++r) {
    CHECK(std::equal(paths[r].at(0), paths[r].at(0) + 3, before[r].at(0)));
    CHECK(std::equal(paths[r].back(), paths[r].back() + 3, before[r].back()));
  }
  CHECK(paths[0].size() == before[0].size());  // a was already straight at full speed
  CHECK(paths[1].size() < before[1].size());   // b sets off earlier...
  CHECK(paths[1].size() > before[0].size());   // ...but not at once: a is in the way
}
