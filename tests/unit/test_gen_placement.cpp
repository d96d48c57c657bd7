// Free-space components and robot placement shared by the generators.
#include <doctest/doctest.h>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/generators.hpp"
#include "earc/gen/placement.hpp"
#include "earc/io/json_io.hpp"
#include "earc/validate/scenario_check.hpp"

using namespace earc;
using namespace earc::gen;

namespace {

// A 10x10 workspace cut in two by a wall x in [4.5, 5.5].
Scenario walledScenario(int robots) {
  Scenario s;
  s.name = "walled";
  s.workspace = {{0, 0}, {10, 10}};
  Obstacle wall;
  wall.type = Obstacle::Type::Box;
  wall.center = {5, 5};
  wall.size = {1, 10};
  s.obstacles.push_back(wall);
  for (int i = 0; i < robots; ++i) s.robots.push_back(mobileRobot(i, {}));
  return s;
}

DiscFree discFreeIn(const CollisionWorld& world) {
  return [&world](geo::Vec2 c, double r) { return world.bodyFree(geo::Body::disc(c, r)); };
}

}  // namespace

TEST_CASE("a wall across the workspace splits the free space into two components") {
  const Scenario s = walledScenario(0);
  const CollisionWorld world(s);
  const FreeSpaceGrid grid(s.workspace, kFreeSpaceCell, 0.36, discFreeIn(world));
  CHECK(grid.componentCount() == 2);
  const int left = grid.componentOf({2, 5}), right = grid.componentOf({8, 5});
  CHECK(left >= 0);
  CHECK(right >= 0);
  CHECK(left != right);
  CHECK(grid.componentOf({2, 9}) == left);
  CHECK(grid.componentOf({5, 5}) == -1);    // inside the wall
  CHECK(grid.componentOf({0.1, 5}) == -1);  // the disc would leave the workspace
  CHECK(grid.componentOf({-1e30, 5}) == -1);
  CHECK(grid.componentOf({5, 1e300}) == -1);
}

TEST_CASE("a gap narrower than the disc keeps the two sides apart, a wide one joins them") {
  for (double gap : {0.6, 1.2}) {
    Scenario s = walledScenario(0);
    s.obstacles[0].size = {1, 10 - gap};
    s.obstacles[0].center = {5, (10 - gap) / 2};
    const CollisionWorld world(s);
    const FreeSpaceGrid grid(s.workspace, kFreeSpaceCell, 0.36, discFreeIn(world));
    CAPTURE(gap);
    CHECK((grid.componentOf({2, 5}) == grid.componentOf({8, 5})) == (gap > 1.0));
  }
}

TEST_CASE("placed robots start and end on the same side of a dividing wall") {
  Scenario s = walledScenario(12);
  const CollisionWorld world(s);
  Random rng(4);
  REQUIRE(placeMobileRobots(s, world, discFreeIn(world), rng));
  CHECK_NOTHROW(checkScenarioGeometry(s, s.name));
  int left = 0;
  for (const auto& r : s.robots) {
    CHECK((r.start[0] < 5) == (r.goal[0] < 5));
    left += r.start[0] < 5;
  }
  CHECK(left > 0);   // both sides are used
  CHECK(left < 12);
}

TEST_CASE("generated coordinates are rounded to four decimals") {
  CHECK(roundCoordinate(1.23456) == 1.2346);
  CHECK(roundCoordinate(-0.00004) == 0.0);
  const Scenario s = generateMobile({});
  for (const auto& r : s.robots)
    for (double v : r.start) CHECK(roundCoordinate(v) == v);
}

TEST_CASE("new starts and goals in a scenario's world: a function of the seed, the world kept, every end valid") {
  MobileSettings mobile;
  mobile.robots = 6;
  mobile.obstacles = 8;
  mobile.seed = 2;
  ArmSettings arms;
  arms.robots = 4;
  arms.obstacles = 2;
  arms.seed = 2;
  for (const Scenario& base : {generateMobile(mobile), generateArms(arms)}) {
    INFO(base.name);
    const Scenario a = redrawStartsAndGoals(base, 7), again = redrawStartsAndGoals(base, 7),
                   other = redrawStartsAndGoals(base, 8);
    CHECK(scenarioToJson(a) == scenarioToJson(again));
    CHECK(scenarioToJson(a) != scenarioToJson(other));
    CHECK(scenarioToJson(a)["obstacles"] == scenarioToJson(base)["obstacles"]);
    REQUIRE(a.robots.size() == base.robots.size());
    bool moved = false;
    for (std::size_t i = 0; i < a.robots.size(); ++i) {
      CHECK(a.robots[i].name == base.robots[i].name);
      moved = moved || a.robots[i].start != base.robots[i].start;
    }
    CHECK(moved);
    // What loadScenario accepts: ends inside, clear, apart.
    CHECK_NOTHROW(scenarioFromJson(scenarioToJson(a), "redrawn"));
  }
}
