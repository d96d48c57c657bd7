// Scenario generators: deterministic per seed, always valid input, and the
// arm layout of the paper's experiments.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/generators.hpp"
#include "earc/gen/placement.hpp"
#include "earc/io/json_io.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/validate/scenario_check.hpp"

using namespace earc;
using namespace earc::gen;

namespace {

Scenario mobile(int robots, int obstacles, std::uint64_t seed, MobileShape shape = MobileShape::Box,
                bool rotated = false) {
  MobileSettings s;
  s.robots = robots;
  s.obstacles = obstacles;
  s.seed = seed;
  s.footprint.shape = shape;
  s.rotated_obstacles = rotated;
  return generateMobile(s);
}

Scenario arms(int robots, int obstacles, std::uint64_t seed, bool rotated = false) {
  ArmSettings s;
  s.robots = robots;
  s.obstacles = obstacles;
  s.seed = seed;
  s.rotated_obstacles = rotated;
  return generateArms(s);
}

std::string text(const Scenario& s) { return scenarioToJson(s).dump(); }

// Smallest distance between two robots' starts (goals) over all pairs.
double closestPair(const Scenario& s, bool goals) {
  const auto models = makeRobotModels(s);
  double best = 1e300;
  for (std::size_t i = 0; i < s.robots.size(); ++i)
    for (std::size_t j = i + 1; j < s.robots.size(); ++j) {
      const auto& qi = goals ? s.robots[i].goal : s.robots[i].start;
      const auto& qj = goals ? s.robots[j].goal : s.robots[j].start;
      best = std::min(best, robotDistance(*models[i], qi.data(), *models[j], qj.data()));
    }
  return best;
}

}  // namespace

TEST_CASE("mobile generator gives the same scenario for the same seed and another for another seed") {
  CHECK(text(mobile(8, 12, 3)) == text(mobile(8, 12, 3)));
  CHECK(text(mobile(8, 12, 3)) != text(mobile(8, 12, 4)));
  CHECK(text(mobile(8, 0, 3)) != text(mobile(8, 0, 4)));
}

TEST_CASE("arms generator gives the same scenario for the same seed and another for another seed") {
  CHECK(text(arms(4, 2, 5)) == text(arms(4, 2, 5)));
  CHECK(text(arms(4, 2, 5)) != text(arms(4, 2, 6)));
  CHECK(text(arms(4, 0, 5)) != text(arms(4, 0, 6)));
}

TEST_CASE("obstacle layouts change with the seed") {
  const Scenario a = mobile(4, 12, 1), b = mobile(4, 12, 2);
  REQUIRE(a.obstacles.size() == 12);
  REQUIRE(b.obstacles.size() == 12);
  CHECK(a.obstacles[0].center != b.obstacles[0].center);
}

TEST_CASE("every generated mobile scenario passes the geometric scenario check") {
  for (int n : {2, 8, 32, 128})
    for (int obstacles : {0, kDefaultMobileObstacles})
      for (std::uint64_t seed : {1, 2, 3}) {
        CAPTURE(n);
        CAPTURE(obstacles);
        CAPTURE(seed);
        const Scenario s = mobile(n, obstacles, seed);
        REQUIRE(s.robots.size() == static_cast<std::size_t>(n));
        CHECK(s.obstacles.size() == static_cast<std::size_t>(obstacles));
        CHECK_NOTHROW(checkScenarioGeometry(s, s.name));
      }
}

TEST_CASE("disc robots and rotated obstacles also give valid mobile scenarios") {
  for (std::uint64_t seed : {1, 2}) {
    const Scenario s = mobile(16, kDefaultMobileObstacles, seed, MobileShape::Disc, true);
    CHECK_NOTHROW(checkScenarioGeometry(s, s.name));
    CHECK(s.robots[0].shape == MobileShape::Disc);
    bool turned = false;
    for (const auto& o : s.obstacles) turned = turned || o.angle != 0.0;
    CHECK(turned);
  }
}

TEST_CASE("every generated arms scenario passes the geometric scenario check") {
  for (int n : {2, 4, 8, 16})
    for (bool with_obstacles : {false, true})
      for (std::uint64_t seed : {1, 2, 3}) {
        CAPTURE(n);
        CAPTURE(with_obstacles);
        CAPTURE(seed);
        const Scenario s = arms(n, with_obstacles ? defaultArmObstacles(n) : 0, seed);
        REQUIRE(s.robots.size() == static_cast<std::size_t>(n));
        CHECK(s.obstacles.size() == (with_obstacles ? static_cast<std::size_t>(defaultArmObstacles(n)) : 0u));
        CHECK_NOTHROW(checkScenarioGeometry(s, s.name));
      }
}

TEST_CASE("generated starts and goals keep the clearance from each other and from the world") {
  for (const Scenario& s : {mobile(32, 12, 9), arms(8, 4, 9)}) {
    CAPTURE(s.name);
    CHECK(closestPair(s, false) > kClearance);
    CHECK(closestPair(s, true) > kClearance);
    const CollisionWorld world(s);
    const auto models = makeRobotModels(s);
    for (std::size_t i = 0; i < s.robots.size(); ++i) {
      CHECK(clearOfWorld(world, *models[i], s.robots[i].start.data()));
      CHECK(clearOfWorld(world, *models[i], s.robots[i].goal.data()));
    }
  }
}

TEST_CASE("arms stand in facing pairs 4.0 apart vertically, pairs 3.0 apart horizontally") {
  const Scenario s = arms(8, 0, 1);
  REQUIRE(s.robots.size() == 8);
  for (std::size_t k = 0; k < 4; ++k) {
    const RobotSpec& lower = s.robots[2 * k];
    const RobotSpec& upper = s.robots[2 * k + 1];
    CHECK(upper.base_position.x == doctest::Approx(lower.base_position.x));
    CHECK(upper.base_position.y - lower.base_position.y == doctest::Approx(4.0));
    CHECK(lower.base_angle == doctest::Approx(std::numbers::pi / 2));
    CHECK(upper.base_angle == doctest::Approx(-std::numbers::pi / 2));
    if (k > 0) {
      CHECK(lower.base_position.x - s.robots[2 * k - 2].base_position.x == doctest::Approx(3.0));
      CHECK(lower.base_position.y == doctest::Approx(s.robots[2 * k - 2].base_position.y));
    }
    CHECK(lower.links == std::vector<double>(5, 0.5));
    CHECK(lower.link_radius == doctest::Approx(0.05));
    CHECK(lower.joint_limits[0].second == doctest::Approx(std::numbers::pi));
    CHECK(lower.joint_limits[1].second == doctest::Approx(2.6));
  }
}

TEST_CASE("the arms workspace holds every arm at full reach with a margin") {
  for (int n : {2, 5, 16}) {
    const Scenario s = arms(n, 0, 1);
    const double reach = 5 * 0.5 + 0.05;
    for (const auto& r : s.robots) {
      CHECK(r.base_position.x - reach > s.workspace.lo.x + 0.1);
      CHECK(r.base_position.x + reach < s.workspace.hi.x - 0.1);
      CHECK(r.base_position.y - reach > s.workspace.lo.y + 0.1);
      CHECK(r.base_position.y + reach < s.workspace.hi.y - 0.1);
    }
  }
}

TEST_CASE("arm obstacles lie between the rows and keep clear of every base") {
  for (std::uint64_t seed : {1, 2, 3, 4}) {
    const Scenario s = arms(8, 6, seed, seed % 2 == 0);
    const double lower = s.robots[0].base_position.y, upper = s.robots[1].base_position.y;
    for (const auto& o : s.obstacles) {
      const geo::Aabb b = geo::bounds(o.body());
      CHECK(b.lo.y > lower);
      CHECK(b.hi.y < upper);
      for (const auto& r : s.robots)
        CHECK(geo::signedDistance(o.body(), geo::Body::disc(r.base_position, 0.0)) >= kArmBaseClearance);
    }
  }
}

TEST_CASE("mobile obstacles lie inside the workspace, rounding included") {
  for (bool rotated : {false, true})
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
      const Scenario s = mobile(2, 40, seed, MobileShape::Box, rotated);
      for (const auto& o : s.obstacles) CHECK(geo::excessOutside(o.body(), s.workspace) <= 0.0);
    }
}

TEST_CASE("scenario names encode family, obstacles, robot count and seed") {
  CHECK(mobile(32, 12, 7).name == "mobile-obst-32-s7");
  CHECK(mobile(4, 0, 1).name == "mobile-4-s1");
  CHECK(mobile(4, 5, 1).name == "mobile-obst5-4-s1");
  CHECK(mobile(4, 0, 2, MobileShape::Disc).name == "mobile-disc-4-s2");
  gen::MobileFootprint big;
  big.shape = MobileShape::Disc;
  big.radius = 0.8;
  CHECK(footprintTag(big) == "-disc-r0.8");  // not named like the 0.3-radius discs
  CHECK(footprintTag({}) == "");
  CHECK(arms(8, 0, 3).name == "arms-8-s3");
  CHECK(arms(8, defaultArmObstacles(8), 3).name == "arms-obst-8-s3");
}

TEST_CASE("generators refuse robot counts outside 2..128") {
  CHECK_THROWS_AS(mobile(1, 0, 1), std::invalid_argument);
  CHECK_THROWS_AS(mobile(129, 0, 1), std::invalid_argument);
  CHECK_THROWS_AS(arms(1, 0, 1), std::invalid_argument);
}

// earc-scenario names the option from setting(): a refusal is bad input.
TEST_CASE("a setting out of range is a SettingError naming the setting") {
  try {
    mobile(1, 0, 1);
    FAIL("1 robot accepted");
  } catch (const SettingError& e) {
    CHECK(e.setting() == "robots");
    CHECK(e.reason() == "must be in [2, 128], got 1");
    CHECK(std::string(e.what()) == "robots must be in [2, 128], got 1");
  }
  MobileSettings s;
  s.robots = 2;
  s.workspace = 2.5;  // smaller than the largest obstacle side (3)...
  CHECK_NOTHROW(generateMobile(s));  // ...which does not matter without obstacles
  s.obstacles = 1;
  CHECK_THROWS_WITH_AS(generateMobile(s), "workspace must be in [3, 1000], got 2.5", SettingError);
}

TEST_CASE("a crowded mobile request fails with a message instead of looping") {
  MobileSettings s;
  s.robots = 128;
  s.workspace = 4.0;
  s.obstacle_max_side = 2.0;
  CHECK_THROWS_AS(generateMobile(s), CrowdedError);
}
