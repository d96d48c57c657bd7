// passThroughWarning: a scenario whose resolution lets a robot cross an
// obstacle between two checked instants is named, and one that does not
// (every generated suite, the example datasets) is not.
#include <doctest/doctest.h>

#include <filesystem>

#include "earc/bench/suites.hpp"
#include "earc/io/json_io.hpp"
#include "earc/scene/pass_through.hpp"
#include "earc/validate/scenario_check.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"

namespace {

// One disc of radius 0.1 left of a wall 0.05 thick that spans the whole
// workspace, its goal right of it.
earc::Scenario discLeftOfThinWall(double translation) {
  earc::Scenario s;
  s.name = "wall";
  s.workspace = {{0, 0}, {10, 10}};
  s.resolution = {translation, 0.05, 0.05};
  s.obstacles.push_back(earc::Obstacle::makeBox({5, 5}, {0.05, 10}));
  earc::RobotSpec r = earc::RobotSpec::mobileDisc("d0", 0.1);
  r.start = {4.3, 5, 0};
  r.goal = {5.7, 5, 0};
  s.robots.push_back(r);
  return s;
}

earc::Path stepsAlongWallAxis(std::initializer_list<double> xs) {
  earc::Path p(3);
  for (double x : xs) {
    const double q[3] = {x, 5, 0};
    p.push(q);
  }
  return p;
}

}  // namespace

TEST_CASE("a resolution coarse enough to step through a wall is warned of, and such a step is valid") {
  earc::Scenario s = discLeftOfThinWall(1.0);
  const std::string w = earc::passThroughWarning(s);
  CHECK(w.find("robot 'd0' can move 0.5 between two checked instants") != std::string::npos);
  CHECK(w.find("obstacle 0's thickness (0.05) and its own (0.2) together") != std::string::npos);
  // The warning is not idle: the contract accepts a path through the wall.
  earc::Solution through;
  through.solved = true;
  through.paths = {stepsAlongWallAxis({4.3, 5.3, 5.7})};
  CHECK(earc::validateSolution(s, through).valid);

  // At half a step of 0.25 the disc cannot clear 0.05 + 0.2: no warning,
  // and the same crossing in steps of 0.5 is caught.
  s = discLeftOfThinWall(0.5);
  CHECK(earc::passThroughWarning(s).empty());
  earc::Solution stepped;
  stepped.solved = true;
  stepped.paths = {stepsAlongWallAxis({4.3, 4.8, 5.3, 5.7})};
  CHECK_FALSE(earc::validateSolution(s, stepped).valid);
}

TEST_CASE("the largest motion of one step counts turning: box corners and every joint of an arm") {
  const earc::Resolution res{0.1, 0.2, 0.05};
  CHECK(earc::largestStepMotion(earc::RobotSpec::mobileDisc("d", 0.3), res) == doctest::Approx(0.1));
  // A 0.6 x 0.8 box: half diagonal 0.5, turned by 0.2.
  CHECK(earc::largestStepMotion(earc::RobotSpec::mobileBox("b", {0.6, 0.8}), res) == doctest::Approx(0.1 + 0.5 * 0.2));
  // Links 1 and 0.5, radius 0.1: joint 2 turns 0.6, joint 1 turns 1.6.
  const earc::RobotSpec arm = earc::RobotSpec::arm("a", {0, 0}, 0, {1.0, 0.5}, 0.1);
  CHECK(earc::largestStepMotion(arm, res) == doctest::Approx(0.05 * 0.6 + 0.05 * 1.6));
  CHECK(earc::thinnestExtent(arm) == doctest::Approx(0.2));
  CHECK(earc::thinnestExtent(earc::RobotSpec::mobileBox("b", {0.6, 0.8})) == doctest::Approx(0.6));
  CHECK(earc::thinnestExtent(earc::Obstacle::makeCircle({0, 0}, 0.25)) == doctest::Approx(0.5));
  // A rotation resolution beyond pi moves a point by at most the diameter.
  CHECK(earc::largestStepMotion(earc::RobotSpec::mobileBox("b", {0.6, 0.8}), {0.1, 10.0, 0.05}) ==
        doctest::Approx(0.1 + 1.0));
}

TEST_CASE("no generated suite and no example scenario is warned of") {
  for (const earc::bench::Suite& suite : earc::bench::allSuites())
    for (int robots : {4, 16}) {
      const earc::Scenario s = earc::bench::trialScenario(suite, robots, 0, 1);
      INFO(s.name);
      CHECK(earc::passThroughWarning(s).empty());
    }
  int examples = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(earc::test::kData).parent_path().parent_path() / "datasets")) {
    if (entry.path().extension() != ".json") continue;
    INFO(entry.path().string());
    CHECK(earc::passThroughWarning(earc::loadScenario(entry.path().string())).empty());
    ++examples;
  }
  CHECK(examples > 0);
}
