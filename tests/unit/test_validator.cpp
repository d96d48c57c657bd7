// validateSolution against hand-made solutions (tests/data/solutions, see
// tests/data/make_fixtures.py) and solutions built in memory.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <numbers>
#include <random>

#include "earc/collision/collision_world.hpp"
#include "earc/io/json_io.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/validate/scenario_check.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"

using earc::test::kData;

using earc::Violation;
using Type = earc::Violation::Type;

namespace {

struct Checked {
  earc::Scenario scenario;
  earc::ValidationReport report;
};

Checked check(const std::string& name, const std::string& solution_case, earc::ValidatorSettings settings = {}) {
  Checked c;
  c.scenario = earc::loadScenario(kData + "/scenarios/" + name + ".json");
  const earc::Solution sol =
      earc::loadSolution(kData + "/solutions/" + name + "__" + solution_case + ".json", &c.scenario);
  c.report = earc::validateSolution(c.scenario, sol, settings);
  return c;
}

bool allOfType(const earc::ValidationReport& r, Type t) {
  return std::all_of(r.violations.begin(), r.violations.end(), [t](const Violation& v) { return v.type == t; });
}

earc::Path path(int dim, std::initializer_list<std::vector<double>> states) {
  earc::Path p(dim);
  for (const auto& s : states) p.push(s.data());
  return p;
}

earc::Scenario discs(int n, double spacing) {
  earc::Scenario s;
  s.name = "discs";
  s.workspace = {{0, 0}, {100, 100}};
  s.resolution = {1.0, 0.5, 0.1};
  for (int i = 0; i < n; ++i) {
    earc::RobotSpec r;
    r.name = "d";
    r.name += std::to_string(i);  // not "d" + ...: GCC 12 warns falsely (-Wrestrict)
    r.radius = 0.3;
    r.start = {1 + spacing * i, 1, 0};
    r.goal = r.start;
    s.robots.push_back(r);
  }
  return s;
}

}  // namespace

TEST_CASE("every fixture marked valid validates") {
  for (const auto& [name, c] : {std::pair{"swap-discs", "valid"}, {"open-disc", "valid"}, {"box-rotation", "valid"},
                                {"arm-fold", "valid"}}) {
    CAPTURE(name);
    const Checked r = check(name, c);
    CHECK(r.report.valid);
    CHECK(r.report.violation_count == 0);
    CHECK(r.report.violations.empty());
  }
}

TEST_CASE("two discs swapping in one step collide only at the midpoint") {
  const Checked r = check("swap-discs", "midpoint-swap");
  CHECK_FALSE(r.report.valid);
  REQUIRE(r.report.violation_count == 1);
  const Violation& v = r.report.violations.at(0);
  CHECK(v.type == Type::RobotRobot);
  CHECK(v.t == 0.5);
  CHECK(v.robots == std::vector<int>{0, 1});
  CHECK(v.amount == doctest::Approx(0.6));
  CHECK(v.detail == "m0 overlaps m1 by 0.6");
}

TEST_CASE("a robot driving into a waiting robot collides at steps and midpoints") {
  const Checked r = check("swap-discs", "head-on");
  REQUIRE(r.report.violation_count == 3);
  CHECK(allOfType(r.report, Type::RobotRobot));
  CHECK(r.report.violations[0].t == 0.5);
  CHECK(r.report.violations[1].t == 1.0);
  CHECK(r.report.violations[2].t == 1.5);
}

TEST_CASE("a box turning in place clips a circle only when rotated") {
  const Checked r = check("box-rotation", "clips-obstacle");
  CHECK(r.report.violation_count == 7);
  CHECK(allOfType(r.report, Type::Obstacle));
  CHECK(r.report.violations.front().t == 2.5);
  CHECK(r.report.violations.front().obstacle == 0);
  CHECK(r.report.violations.front().robots == std::vector<int>{0});
}

TEST_CASE("an arm folding too far collides with itself") {
  const Checked r = check("arm-fold", "self-collision");
  CHECK(r.report.violation_count == 25);
  CHECK(allOfType(r.report, Type::SelfCollision));
  CHECK(r.report.violations.front().t == 20);
  CHECK(r.report.violations.front().detail.starts_with("a0 links 1 and 4 overlap by"));
}

TEST_CASE("an arm raised through an obstacle hits it with its last link") {
  const Checked r = check("arm-fold", "hits-obstacle");
  CHECK(r.report.violation_count == 5);
  CHECK(allOfType(r.report, Type::Obstacle));
  CHECK(r.report.violations.front().detail.starts_with("a0 link 4 overlaps obstacle #0 (box)"));
}

TEST_CASE("joints outside their limits are reported per joint and step") {
  const Checked r = check("arm-fold", "joint-limit");
  REQUIRE(r.report.violation_count == 3);
  CHECK(allOfType(r.report, Type::JointLimit));
  CHECK(r.report.violations[0].t == 6);
  CHECK(r.report.violations[0].joint == 3);
  CHECK(r.report.violations[1].amount == doctest::Approx(0.7));
}

TEST_CASE("steps larger than the resolution are reported at the step's start") {
  const Checked disc = check("open-disc", "resolution");
  REQUIRE(disc.report.violation_count == 1);
  CHECK(disc.report.violations[0].type == Type::Resolution);
  CHECK(disc.report.violations[0].t == 0);
  CHECK(disc.report.violations[0].amount == doctest::Approx(0.8));
  const Checked arm = check("arm-fold", "resolution");
  CHECK(arm.report.violation_count == 5);
  CHECK(arm.report.violations[0].joint == 1);
}

TEST_CASE("a path that ends away from the goal or starts away from the start is invalid") {
  const Checked goal = check("open-disc", "wrong-goal");
  REQUIRE(goal.report.violation_count == 1);
  CHECK(goal.report.violations[0].type == Type::Goal);
  CHECK(goal.report.violations[0].t == 11);
  const Checked start = check("open-disc", "wrong-start");
  REQUIRE(start.report.violation_count == 1);
  CHECK(start.report.violations[0].type == Type::Start);
}

TEST_CASE("a disc leaving the workspace is reported at steps and midpoints") {
  const Checked r = check("open-disc", "leaves-workspace");
  CHECK(r.report.violation_count == 8);
  CHECK(allOfType(r.report, Type::Workspace));
  CHECK(r.report.violations.front().t == 1.5);
  CHECK(r.report.violations[1].amount == doctest::Approx(0.2));
}

TEST_CASE("a heading that crosses the +-pi seam and ends 2 pi off the goal is accepted") {
  const Checked r = check("open-disc", "heading-wrap");
  CHECK(r.report.valid);
  CHECK(r.report.makespan == 11);
}

TEST_CASE("structural problems are violations: not solved, missing, out of order, unknown, other scenario") {
  const Checked ns = check("swap-discs", "not-solved");
  REQUIRE(ns.report.violation_count == 1);
  CHECK(ns.report.violations[0].type == Type::NotSolved);
  const Checked missing = check("swap-discs", "missing-path");
  REQUIRE(missing.report.violation_count == 1);
  CHECK(missing.report.violations[0].type == Type::Paths);
  CHECK(missing.report.violations[0].robots == std::vector<int>{1});
  const Checked order = check("swap-discs", "wrong-order");
  CHECK(order.report.violation_count == 2);
  CHECK(allOfType(order.report, Type::Paths));
  const Checked unknown = check("swap-discs", "unknown-robot");
  REQUIRE(unknown.report.violation_count == 1);
  CHECK(unknown.report.violations[0].detail == "path for unknown robot 'ghost'");
  const Checked other = check("swap-discs", "other-scenario");
  REQUIRE(other.report.violation_count == 1);
  CHECK(other.report.violations[0].type == Type::ScenarioName);
}

TEST_CASE("a solution built in memory is validated in the scenario's order") {
  const earc::Scenario sc = earc::loadScenario(kData + "/scenarios/swap-discs.json");
  earc::Solution s;
  s.solved = true;
  s.paths = {path(3, {{2, 5, 0}, {3, 5, 0}}), path(3, {{3, 5, 0}, {3, 6, 0}, {2, 6, 0}, {2, 5, 0}})};
  earc::ValidationReport r = earc::validateSolution(sc, s);
  CHECK(r.valid);
  CHECK(r.makespan == 3);
  CHECK(r.sum_of_costs == 4);
  CHECK(r.total_distance == doctest::Approx(4.0));

  std::swap(s.paths[0], s.paths[1]);  // now the paths do not start at their robots' starts
  r = earc::validateSolution(sc, s);
  CHECK_FALSE(r.valid);
  CHECK(r.violations[0].type == Type::Start);

  s.paths.resize(1);
  r = earc::validateSolution(sc, s);
  CHECK(std::any_of(r.violations.begin(), r.violations.end(),
                    [](const Violation& v) { return v.type == Type::Paths && v.robots == std::vector<int>{1}; }));
}

TEST_CASE("a robot that has finished stays at its goal and can still be hit") {
  const earc::Scenario sc = discs(2, 2.0);  // d0 at (1, 1), d1 at (3, 1)
  earc::Solution s;
  s.solved = true;
  // d0's path is its start alone, so it waits there while d1 drives over
  // it and back (contact at t = 1.5, 2 and 2.5).
  s.paths = {path(3, {{1, 1, 0}}), path(3, {{3, 1, 0}, {2, 1, 0}, {1, 1, 0}, {2, 1, 0}, {3, 1, 0}})};
  const earc::ValidationReport r = earc::validateSolution(sc, s);
  REQUIRE_FALSE(r.valid);
  CHECK(allOfType(r, Type::RobotRobot));
  CHECK(r.violations.front().t == 1.5);
  CHECK(r.violations.back().t == 2.5);
  CHECK(r.violation_count == 3);
}

TEST_CASE("violations are listed earliest first, capped, and all are counted") {
  earc::ValidatorSettings settings;
  settings.max_listed = 4;
  const Checked r = check("arm-fold", "self-collision", settings);
  CHECK(r.report.violation_count == 25);
  REQUIRE(r.report.violations.size() == 4);
  for (std::size_t i = 1; i < r.report.violations.size(); ++i)
    CHECK(r.report.violations[i - 1].t <= r.report.violations[i].t);
}

TEST_CASE("the sweep over bounding discs finds exactly the pairs that all-pairs testing finds") {
  // 60 discs on a random walk in a small square: many contacts. Short
  // steps keep the discs' order by x nearly the same from one instant to
  // the next; jumps across the square reorder them completely.
  double reach = 0.5;
  SUBCASE("short steps") { reach = 0.5; }
  SUBCASE("jumps across the square") { reach = 11.0; }
  earc::Scenario sc = discs(60, 0.0);
  sc.workspace = {{0, 0}, {12, 12}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.5, 11.5), step(-reach, reach);
  earc::Solution s;
  s.solved = true;
  const int steps = 30;
  for (auto& r : sc.robots) {
    r.radius = 0.2 + 0.1 * static_cast<double>((&r - sc.robots.data()) % 3);
    earc::Path p(3);
    double q[3] = {u(rng), u(rng), 0};
    r.start = {q[0], q[1], 0};
    for (int t = 0; t <= steps; ++t) {
      p.push(q);
      q[0] = std::clamp(q[0] + step(rng), 0.5, 11.5);
      q[1] = std::clamp(q[1] + step(rng), 0.5, 11.5);
    }
    r.goal = {p.back()[0], p.back()[1], 0};
    s.paths.push_back(p);
  }
  const earc::ValidationReport rep = earc::validateSolution(sc, s, {.max_listed = 1000000});
  const auto models = earc::makeRobotModels(sc);
  std::size_t expected = 0;
  std::vector<double> qa(3), qb(3);
  for (int k = 0; k <= 2 * steps; ++k)
    for (std::size_t i = 0; i < sc.robots.size(); ++i)
      for (std::size_t j = i + 1; j < sc.robots.size(); ++j) {
        models[i]->interpolate(s.paths[i].at(k / 2), s.paths[i].at(k / 2 + 1), 0.5 * (k % 2), qa.data());
        models[j]->interpolate(s.paths[j].at(k / 2), s.paths[j].at(k / 2 + 1), 0.5 * (k % 2), qb.data());
        expected += earc::robotDistance(*models[i], qa.data(), *models[j], qb.data()) < -1e-6;
      }
  REQUIRE(expected > 100);
  std::size_t found = 0;
  for (const Violation& v : rep.violations) found += v.type == Type::RobotRobot;
  CHECK(found == expected);
}

TEST_CASE("violation type names match the independent checker's") {
  CHECK(std::string(earc::violationTypeName(Type::RobotRobot)) == "robot-robot");
  CHECK(std::string(earc::violationTypeName(Type::SelfCollision)) == "self-collision");
  CHECK(std::string(earc::violationTypeName(Type::JointLimit)) == "joint-limit");
  CHECK(std::string(earc::violationTypeName(Type::NotSolved)) == "not-solved");
  CHECK(std::string(earc::violationTypeName(Type::ScenarioName)) == "scenario-name");
}

TEST_CASE("a robot standing still is checked again at every instant it stands in an obstacle") {
  // d0 waits clear, drives into a circle, waits in it, waits clear again;
  // d1 waits outside the workspace the whole time. Instants k = 0 .. 20.
  earc::Scenario sc = discs(2, 4.0);  // d0 at (1, 1), d1 at (5, 1)
  sc.workspace = {{0, 0}, {5.1, 10}};
  sc.obstacles = {earc::Obstacle::makeCircle({3, 1}, 0.5)};
  earc::Solution s;
  s.solved = true;
  s.paths = {path(3, {{1, 1, 0}, {1, 1, 0}, {1, 1, 0}, {2, 1, 0}, {3, 1, 0}, {3, 1, 0}, {3, 1, 0}, {3, 1, 0},
                      {2, 1, 0}, {1, 1, 0}, {1, 1, 0}}),
             path(3, {{5, 1, 0}})};
  sc.robots[0].goal = {1, 1, 0};
  const earc::ValidationReport r = earc::validateSolution(sc, s, {.max_listed = 1000});
  // In the circle (centres 0.8 or less apart) from t = 3.5 to 7.5: 9 instants.
  std::size_t obstacle = 0, workspace = 0;
  for (const Violation& v : r.violations) {
    obstacle += v.type == Type::Obstacle;
    workspace += v.type == Type::Workspace;
  }
  CHECK(obstacle == 9);
  CHECK(workspace == 21);
  CHECK(r.violation_count == obstacle + workspace);
}
