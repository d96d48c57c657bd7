// Collision checking with the contract's semantics: obstacles, workspace
// slack, self-collision, motions sampled at steps and midpoints, and
// robot-robot contact.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <thread>

#include "../../src/collision/obstacle_cells.hpp"
#include "earc/collision/collision_world.hpp"
#include "support.hpp"

using earc::test::kPi;

using namespace earc;

namespace {

Obstacle boxObstacle(geo::Vec2 c, geo::Vec2 size, double angle = 0.0) { return Obstacle::makeBox(c, size, angle); }
Obstacle circleObstacle(geo::Vec2 c, double r) { return Obstacle::makeCircle(c, r); }

Scenario world(std::vector<Obstacle> obstacles, geo::Aabb ws = {{0, 0}, {10, 10}}) {
  Scenario s;
  s.name = "test";
  s.workspace = ws;
  s.obstacles = std::move(obstacles);
  return s;
}

std::unique_ptr<RobotModel> disc(double r) { return makeRobotModel(RobotSpec::mobileDisc("disc", r), {}); }
std::unique_ptr<RobotModel> box(double length, double width) {
  return makeRobotModel(RobotSpec::mobileBox("box", {length, width}), {});
}
std::unique_ptr<RobotModel> arm(std::vector<double> links, double r, geo::Vec2 base, double base_angle = 0.0) {
  return makeRobotModel(RobotSpec::arm("arm", base, base_angle, std::move(links), r), {});
}

}  // namespace

TEST_CASE("a disc flush against a box obstacle is valid, 2e-6 closer it is not") {
  const CollisionWorld w(world({boxObstacle({5, 5}, {2, 2})}));
  auto robot = disc(0.5);
  const double flush[] = {6.5, 5, 0};
  const double into[] = {6.5 - 2e-6, 5, 0};
  CHECK(w.stateValid(*robot, flush));
  CHECK_FALSE(w.stateValid(*robot, into));
}

TEST_CASE("a box robot turned 45 degrees clips an obstacle corner its axis-aligned box would miss") {
  // The robot's end face, 0.3 from its centre along (1,1)/sqrt 2, reaches
  // 0.3 - 0.2 sqrt 2 = 0.017 past the obstacle's corner (6, 6).
  const CollisionWorld w(world({boxObstacle({5, 5}, {2, 2})}));
  auto robot = box(0.6, 0.4);
  const double clipping[] = {6.2, 6.2, kPi / 4};
  const double clear[] = {6.3, 6.3, kPi / 4};
  CHECK_FALSE(w.stateValid(*robot, clipping));
  CHECK(w.stateValid(*robot, clear));
}

TEST_CASE("an arm link crossing a circle obstacle makes the state invalid") {
  const CollisionWorld w(world({circleObstacle({6.5, 5}, 0.2)}));
  auto robot = arm({1, 1}, 0.05, {5, 5});
  const double straight[] = {0, 0};   // link 2 runs (6,5)-(7,5) through the circle
  const double raised[] = {0, kPi / 2};
  CHECK_FALSE(w.stateValid(*robot, straight));
  CHECK(w.stateValid(*robot, raised));
}

TEST_CASE("a robot 1e-7 outside the workspace is allowed") {
  const CollisionWorld w(world({}));
  const double q[] = {0.5 - 1e-7, 5, 0};
  CHECK(w.stateValid(*disc(0.5), q));
}

TEST_CASE("a robot 1e-5 outside the workspace is rejected") {
  const CollisionWorld w(world({}));
  const double q[] = {0.5 - 1e-5, 5, 0};
  CHECK_FALSE(w.stateValid(*disc(0.5), q));
}

TEST_CASE("a configuration with NaN coordinates is never valid") {
  const CollisionWorld w(world({}));
  const double q[] = {std::nan(""), 5, 0};
  CHECK_FALSE(w.stateValid(*disc(0.5), q));
}

TEST_CASE("a folded arm is an invalid state") {
  const CollisionWorld w(world({}, {{-5, -5}, {5, 5}}));
  auto robot = arm({2, 1, 2}, 0.05, {0, 0});
  const double folded[] = {0, 2.5, 2.0};
  CHECK_FALSE(w.stateValid(*robot, folded));
}

TEST_CASE("an arm outside its joint limits is an invalid state") {
  const CollisionWorld w(world({}, {{-5, -5}, {5, 5}}));
  auto robot = arm({1, 1}, 0.05, {0, 0});
  const double beyond[] = {kPi + 1e-3, 0};
  CHECK_FALSE(w.stateValid(*robot, beyond));
}

TEST_CASE("motionValid catches a motion whose midpoint alone collides") {
  // One step of 0.05 past a circle: centre gaps 0.2016 at both ends (clear of
  // 0.1 + 0.101) but 0.2 at the midpoint (0.001 overlap).
  const CollisionWorld w(world({circleObstacle({1.025, 5.2}, 0.101)}));
  auto robot = disc(0.1);
  const double a[] = {1.0, 5, 0};
  const double b[] = {1.05, 5, 0};
  REQUIRE(robot->stepsBetween(a, b) == 1);
  REQUIRE(w.stateValid(*robot, a));
  REQUIRE(w.stateValid(*robot, b));
  CHECK_FALSE(w.motionValid(*robot, a, b));
  CHECK(w.countInvalidInstants(*robot, a, b) == 1);
}

TEST_CASE("countInvalidInstants counts every step and midpoint of a blocked motion") {
  const CollisionWorld w(world({boxObstacle({5, 5}, {4, 4})}));
  auto robot = disc(0.1);
  const double a[] = {4.0, 5, 0};
  const double b[] = {4.15, 5, 0};  // 3 steps: 7 instants, all inside
  REQUIRE(robot->stepsBetween(a, b) == 3);
  CHECK(w.countInvalidInstants(*robot, a, b) == 7);
}

TEST_CASE("a motion between equal configurations checks just that configuration") {
  const CollisionWorld w(world({boxObstacle({5, 5}, {4, 4})}));
  auto robot = disc(0.1);
  const double inside[] = {5, 5, 0};
  const double free[] = {1, 1, 0};
  CHECK(w.countInvalidInstants(*robot, inside, inside) == 1);
  CHECK(w.motionValid(*robot, free, free));
}

TEST_CASE("touchedObstacles lists every touched obstacle in ascending order") {
  const CollisionWorld w(world({boxObstacle({5, 5}, {1, 1}), circleObstacle({1, 1}, 0.5), circleObstacle({5.8, 5}, 0.3)}));
  std::vector<int> hit;
  w.touchedObstacles(geo::Body::disc({5.4, 5}, 0.2), hit);
  CHECK(hit == std::vector<int>{0, 2});
}

TEST_CASE("two discs touch when they overlap by more than the tolerance") {
  auto a = disc(0.5);
  auto b = disc(0.3);
  const double qa[] = {1, 1, 0};
  const double near[] = {1.8 - 2e-6, 1, 0};
  const double flush[] = {1.8, 1, 0};
  CHECK(robotsTouch(*a, qa, *b, near));
  CHECK_FALSE(robotsTouch(*a, qa, *b, flush));
}

TEST_CASE("a disc and a box robot touch only where the box's heading puts its length") {
  auto a = disc(0.2);
  auto b = box(1.0, 0.2);
  const double qa[] = {0, 0.65, 0};
  const double lengthwise_up[] = {0, 0, kPi / 2};  // reaches y = 0.5, disc starts at 0.45
  const double across[] = {0, 0, 0};               // reaches y = 0.1
  CHECK(robotsTouch(*a, qa, *b, lengthwise_up));
  CHECK_FALSE(robotsTouch(*a, qa, *b, across));
}

TEST_CASE("a box robot's heading decides whether it touches its neighbour") {
  auto a = box(0.6, 0.4);
  auto b = box(0.6, 0.4);
  const double qa[] = {0, 0, 0};           // x in [-0.3, 0.3]
  const double lengthwise[] = {0.55, 0, 0};  // x from 0.25: 0.05 overlap
  const double crosswise[] = {0.55, 0, kPi / 2};  // x from 0.35: 0.05 apart
  CHECK(robotsTouch(*a, qa, *b, lengthwise));
  CHECK_FALSE(robotsTouch(*a, qa, *b, crosswise));
  CHECK(robotDistance(*a, qa, *b, crosswise) == doctest::Approx(0.05));
}

TEST_CASE("an arm touches a disc robot sitting on its last link") {
  auto a = arm({1, 1}, 0.05, {0, 0});
  auto d = disc(0.1);
  const double q[] = {0, kPi / 2};  // link 2 runs (1,0)-(1,1)
  const double on_link[] = {1.1, 0.5, 0};
  const double beside[] = {1.2, 0.5, 0};
  CHECK(robotsTouch(*a, q, *d, on_link));
  CHECK_FALSE(robotsTouch(*a, q, *d, beside));
  CHECK(robotDistance(*a, q, *d, beside) == doctest::Approx(0.05));
}

TEST_CASE("two arms touch when their links cross and not when they run parallel") {
  // Arm b faces arm a from (2, 0); its line y = -tan(0.3)(x - 2) crosses a's
  // y = tan(0.3) x at x = 1, while y = tan(0.3)(x - 2) runs 0.59 beside it.
  auto a = arm({1, 1}, 0.05, {0, 0});
  auto b = arm({1, 1}, 0.05, {2, 0}, kPi);
  const double qa[] = {0.3, 0};
  const double crossing[] = {-0.3, 0};
  const double parallel[] = {0.3, 0};
  CHECK(robotsTouch(*a, qa, *b, crossing));
  CHECK_FALSE(robotsTouch(*a, qa, *b, parallel));
}

TEST_CASE("robotsTouch agrees with robotDistance on random disc, box and arm pairs") {
  std::unique_ptr<RobotModel> models[] = {disc(0.3), box(0.6, 0.4), arm({0.8, 0.6, 0.5}, 0.06, {2, 2}, 0.4),
                                          arm({1.0, 0.7}, 0.1, {3, 1}, -2.0)};
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> pos(0.0, 4.0), ang(-kPi, kPi);
  int touching = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const RobotModel& a = *models[static_cast<std::size_t>(trial) % 4];
    const RobotModel& b = *models[static_cast<std::size_t>(trial / 4) % 4];
    std::vector<double> qa(static_cast<std::size_t>(a.dim())), qb(static_cast<std::size_t>(b.dim()));
    for (auto* q : {&qa, &qb})
      for (double& v : *q) v = ang(rng);
    if (a.isMobile()) qa[0] = pos(rng), qa[1] = pos(rng);
    if (b.isMobile()) qb[0] = pos(rng), qb[1] = pos(rng);
    const bool touch = robotsTouch(a, qa.data(), b, qb.data());
    CHECK(touch == (robotDistance(a, qa.data(), b, qb.data()) < -geo::kContactTolerance));
    touching += touch;
  }
  CHECK(touching > 200);
  CHECK(touching < 3800);
}

namespace {

Scenario randomBoxWorld(std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(0.0, 20.0), size(0.1, 1.2), ang(-kPi, kPi);
  std::vector<Obstacle> obs;
  for (std::size_t i = 0; i < count; ++i) {
    if (i % 4 == 3) obs.push_back(circleObstacle({pos(rng), pos(rng)}, 0.5 * size(rng)));
    else obs.push_back(boxObstacle({pos(rng), pos(rng)}, {size(rng), size(rng)}, ang(rng)));
  }
  return world(std::move(obs), {{0, 0}, {20, 20}});
}

}  // namespace

TEST_CASE("the FCL tree and the plain loop find the same touched obstacles") {
  const Scenario s = randomBoxWorld(300, 17);
  const CollisionWorld tree(s, CollisionWorld::BroadphaseMode::Tree);
  const CollisionWorld loop(s, CollisionWorld::BroadphaseMode::Loop);
  REQUIRE(tree.usesTree());
  REQUIRE_FALSE(loop.usesTree());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(0.0, 20.0), ang(-kPi, kPi), len(0.0, 2.0);
  int touching = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const geo::Vec2 c{pos(rng), pos(rng)};
    const double a = ang(rng);
    const geo::Body b = trial % 2 ? geo::Body::box(c, {0.3, 0.2}, a)
                                  : geo::Body::capsule(c, c + geo::Vec2{std::cos(a), std::sin(a)} * len(rng), 0.05);
    std::vector<int> from_tree, from_loop;
    tree.touchedObstacles(b, from_tree);
    loop.touchedObstacles(b, from_loop);
    CHECK(from_tree == from_loop);
    CHECK(tree.bodyFree(b) == loop.bodyFree(b));
    touching += !from_tree.empty();
  }
  CHECK(touching > 100);  // the comparison saw real contacts
}

TEST_CASE("the obstacle-cell table says no only for boxes that meet no bound") {
  // Unit cells on a lattice (as a MovingAI map's), some flush against each
  // other, and queries on, between and exactly at the cells' edges.
  std::mt19937 rng(5);
  std::vector<geo::Aabb> bounds;
  std::uniform_int_distribution<int> cellPick(0, 39);
  for (int i = 0; i < 300; ++i) {
    const double x = cellPick(rng), y = cellPick(rng) * 0.5;
    bounds.push_back({{x, y}, {x + 1.0, y + 1.0}});
  }
  const earc::ObstacleCells cells(bounds, std::size_t{1} << 14);
  REQUIRE(cells.columns() > 0);
  std::uniform_real_distribution<double> pos(-2.0, 43.0), size(0.0, 1.5);
  std::uniform_int_distribution<int> quarter(-8, 172);
  int no = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    geo::Aabb q;
    if (trial % 2) {
      q.lo = {pos(rng), pos(rng) * 0.5};
      q.hi = q.lo + geo::Vec2{size(rng), size(rng)};
    } else {  // corners on quarter cells: many boxes touch a bound's edge exactly
      q.lo = {quarter(rng) * 0.25, quarter(rng) * 0.125};
      q.hi = q.lo + geo::Vec2{0.25 * (trial % 5), 0.125 * (trial % 3)};
    }
    const bool meets = std::any_of(bounds.begin(), bounds.end(), [&](const geo::Aabb& b) { return b.overlaps(q); });
    if (!cells.mayMeet(q)) {
      ++no;
      CHECK_FALSE(meets);
    }
  }
  CHECK(no > 2000);  // the table does answer no, not only maybe
  CHECK(cells.mayMeet({{std::nan(""), 0.0}, {1.0, 1.0}}));
  CHECK_FALSE(earc::ObstacleCells({}, 100).mayMeet({{0, 0}, {1, 1}}));
}

TEST_CASE("the tree with its cell table and the plain loop agree on a grid map's aisles") {
  // Walls of unit cells with one-cell aisles between them; discs at cell
  // centres and half way between, flush with and 1e-6 into a wall.
  std::vector<Obstacle> obs;
  for (int x = 0; x < 40; x += 2)
    for (int y = 1; y < 39; ++y) obs.push_back(boxObstacle({x + 0.5, y + 0.5}, {1.0, 1.0}));
  const Scenario s = world(std::move(obs), {{0, 0}, {40, 40}});
  const CollisionWorld tree(s, CollisionWorld::BroadphaseMode::Tree);
  const CollisionWorld loop(s, CollisionWorld::BroadphaseMode::Loop);
  int touching = 0, clear = 0;
  for (int x = 0; x < 80; ++x)
    for (int y = 0; y < 80; ++y)
      for (const double r : {0.3, 0.5, 0.5 + 2e-6, 0.7}) {
        const geo::Body b = geo::Body::disc({x * 0.5 + 0.5, y * 0.5}, r);
        std::vector<int> from_tree, from_loop;
        tree.touchedObstacles(b, from_tree);
        loop.touchedObstacles(b, from_loop);
        CHECK(from_tree == from_loop);
        CHECK(tree.bodyFree(b) == loop.bodyFree(b));
        (from_tree.empty() ? clear : touching) += 1;
      }
  CHECK(touching > 1000);
  CHECK(clear > 1000);
}

TEST_CASE("the automatic broad phase switches to the tree for large obstacle counts") {
  CHECK_FALSE(CollisionWorld(randomBoxWorld(8, 1)).usesTree());
  CHECK(CollisionWorld(randomBoxWorld(1000, 1)).usesTree());
}

TEST_CASE("concurrent stateValid calls answer as sequential ones do") {
  const CollisionWorld w(randomBoxWorld(1000, 9));
  auto robot = box(0.6, 0.4);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(0.0, 20.0), ang(-kPi, kPi);
  std::vector<double> qs;
  for (int i = 0; i < 4000; ++i) qs.insert(qs.end(), {pos(rng), pos(rng), ang(rng)});
  std::vector<char> expected(4000), first(4000), second(4000);
  for (std::size_t i = 0; i < 4000; ++i) expected[i] = w.stateValid(*robot, &qs[3 * i]);
  auto run = [&](std::vector<char>& out) {
    for (std::size_t i = 0; i < 4000; ++i) out[i] = w.stateValid(*robot, &qs[3 * i]);
  };
  std::thread t1(run, std::ref(first));
  std::thread t2(run, std::ref(second));
  t1.join();
  t2.join();
  CHECK(first == expected);
  CHECK(second == expected);
}
