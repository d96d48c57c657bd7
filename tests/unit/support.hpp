// Helpers shared by the unit tests. One definition each: CI compiles the
// tests as a unity build, where a helper defined in two test files (even
// in anonymous namespaces) would be defined twice in one translation unit.
// Which files share a batch changes as files are added, so a test file's
// own helpers need names no other test file uses.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "earc/experience/keys.hpp"
#include "earc/experience/store.hpp"
#include "earc/planning/crowd_roadmap.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/scene/scenario.hpp"

namespace earc::test {

// tests/unit/data: scenarios, solutions and databases the tests read.
inline const std::string kData = EARC_TEST_DATA_DIR;

// A path through the given states, one per step.
inline Path line(const std::vector<std::vector<double>>& states) {
  Path p(static_cast<int>(states.front().size()));
  for (const auto& q : states) p.push(q.data());
  return p;
}

// A straight path of `steps` states from a to b, ending exactly at b.
inline Path line(const std::vector<double>& a, const std::vector<double>& b, int steps) {
  Path p(static_cast<int>(a.size()));
  for (int t = 0; t < steps; ++t) {
    std::vector<double> q(a.size());
    for (std::size_t d = 0; d < a.size(); ++d) q[d] = t == steps - 1 ? b[d] : a[d] + (b[d] - a[d]) * t / (steps - 1);
    p.push(q);
  }
  return p;
}

inline constexpr double kPi = std::numbers::pi;

// An arm of five links of 0.5 (radius 0.05), the generator's arm, at
// `base` facing `angle`, from `start` to `goal`.
inline RobotSpec fiveLinkArm(const std::string& name, geo::Vec2 base, double angle, std::vector<double> start,
                             std::vector<double> goal) {
  RobotSpec s;
  s.name = name;
  s.kind = RobotKind::Manipulator;
  s.base_position = base;
  s.base_angle = angle;
  s.links = {0.5, 0.5, 0.5, 0.5, 0.5};
  s.link_radius = 0.05;
  s.joint_limits = {{-3.14159, 3.14159}, {-2.6, 2.6}, {-2.6, 2.6}, {-2.6, 2.6}, {-2.6, 2.6}};
  s.start = std::move(start);
  s.goal = std::move(goal);
  return s;
}

// The experience-class traits of a mobile disc robot.
inline exp::RobotTraits discTraits(double radius = 0.3) {
  RobotSpec s;
  s.radius = radius;
  return exp::traitsOf(*makeRobotModel(s, Resolution{}));
}

inline exp::StoreOptions readOnly() {
  exp::StoreOptions o;
  o.read_only = true;
  return o;
}

// The file's bytes; a file that cannot be opened fails the test.
inline std::string readFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  REQUIRE(in.good());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A scratch directory removed with everything in it at the end of scope.
struct TempDb {
  std::filesystem::path dir;
  TempDb() {
    char tmpl[] = "/tmp/earc-test-XXXXXX";
    dir = mkdtemp(tmpl);
  }
  ~TempDb() { std::filesystem::remove_all(dir); }
  std::string file(const std::string& name = "exp.db") const { return (dir / name).string(); }
};

// A grid world of `rows` (row 0 on top, '#' blocked) as a scenario, one
// box per blocked cell, and robots between the given cells.
inline Scenario gridScenario(const std::vector<std::string>& rows,
                             const std::vector<std::pair<geo::Vec2, geo::Vec2>>& moves, RobotSpec shape) {
  Scenario sc;
  sc.name = "grid";
  const int h = static_cast<int>(rows.size()), w = static_cast<int>(rows.front().size());
  sc.workspace = {{0, 0}, {static_cast<double>(w), static_cast<double>(h)}};
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      if (rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)] == '#')
        sc.obstacles.push_back(Obstacle::makeBox({c + 0.5, h - 1 - r + 0.5}, {1, 1}));
  for (std::size_t i = 0; i < moves.size(); ++i) {
    RobotSpec s = shape;
    s.name = "m" + std::to_string(i);
    s.start = {moves[i].first.x, moves[i].first.y, 0.0};
    s.goal = {moves[i].second.x, moves[i].second.y, 0.0};
    sc.robots.push_back(s);
  }
  return sc;
}

// Every robot's index in a scenario, and every robot's start (or goal).
inline std::vector<int> allRobots(const Scenario& sc) {
  std::vector<int> g(sc.robots.size());
  for (std::size_t i = 0; i < g.size(); ++i) g[i] = static_cast<int>(i);
  return g;
}
inline std::vector<std::vector<double>> robotEnds(const Scenario& sc, bool starts) {
  std::vector<std::vector<double>> out;
  for (const auto& r : sc.robots) out.push_back(starts ? r.start : r.goal);
  return out;
}

// Whether no two robots' steps between consecutive configurations (vertex per
// robot) of the roadmap conflict.
inline bool latticeStepsConflictFree(const CrowdRoadmap& rm, const std::vector<std::vector<int>>& configs) {
  const int n = rm.robotCount();
  for (std::size_t t = 0; t + 1 < configs.size(); ++t)
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (rm.conflict(i, {configs[t][static_cast<std::size_t>(i)], configs[t + 1][static_cast<std::size_t>(i)]}, j,
                        {configs[t][static_cast<std::size_t>(j)], configs[t + 1][static_cast<std::size_t>(j)]}))
          return false;
  return true;
}

// `n` robots between the free cells of `rows` (as gridScenario), starts and
// goals each a random permutation of the cells by `seed`.
inline std::vector<std::pair<geo::Vec2, geo::Vec2>> shuffledMoves(const std::vector<std::string>& rows, int n,
                                                                  std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const int h = static_cast<int>(rows.size()), w = static_cast<int>(rows.front().size());
  std::vector<geo::Vec2> cells;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      if (rows[static_cast<std::size_t>(h - 1 - r)][static_cast<std::size_t>(c)] == '.') cells.push_back({c + 0.5, r + 0.5});
  std::vector<geo::Vec2> goals = cells;
  std::shuffle(cells.begin(), cells.end(), rng);
  std::shuffle(goals.begin(), goals.end(), rng);
  std::vector<std::pair<geo::Vec2, geo::Vec2>> moves;
  for (int i = 0; i < n; ++i) moves.push_back({cells[static_cast<std::size_t>(i)], goals[static_cast<std::size_t>(i)]});
  return moves;
}

}  // namespace earc::test
