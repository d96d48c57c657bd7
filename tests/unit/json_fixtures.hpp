// Helpers shared by the scenario and solution file tests (test_json_io.cpp,
// test_json_warnings.cpp, test_solution_io.cpp).
#pragma once

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "earc/bench/suites.hpp"
#include "earc/io/json_io.hpp"
#include "earc/validate/scenario_check.hpp"
#include "support.hpp"

using earc::InputError;
using nlohmann::json;

namespace earc::json_test {

inline json validScenario() {
  return json::parse(R"({
    "format": "earc.scenario.v1", "name": "t",
    "workspace": {"min": [0, 0], "max": [10, 10]},
    "resolution": {"translation": 0.1, "rotation": 0.2, "joint": 0.3},
    "obstacles": [{"type": "box", "center": [5, 5], "size": [1, 2], "angle": 0.5},
                  {"type": "circle", "center": [8, 2], "radius": 0.5}],
    "robots": [
      {"name": "m0", "type": "mobile", "shape": {"type": "disc", "radius": 0.3},
       "start": [1, 1, 0], "goal": [9, 9, 1]},
      {"name": "m1", "type": "mobile", "shape": {"type": "box", "size": [0.8, 0.4]},
       "start": [1, 9, 0], "goal": [9, 1, 3]},
      {"name": "a0", "type": "manipulator", "base": [2, 5, 0], "links": [1, 0.5], "link_radius": 0.1,
       "joint_limits": [[-3, 3], [-2, 2]], "start": [0, 0], "goal": [0.5, -0.5]}
    ]})");
}

// The message of the InputError that reading doc throws ("" when none).
inline std::string scenarioError(const json& doc) {
  try {
    earc::scenarioFromJson(doc, "in.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

inline std::string geometryError(const json& doc) {
  try {
    earc::checkScenarioGeometry(earc::scenarioFromJson(doc, "in.json"), "in.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

inline std::string parseError(const std::string& text) {
  try {
    earc::parseJsonText(text, "in.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

inline bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Checks that the error names the file, the path and the reason.
#define CHECK_ERROR(message, path, reason)                         \
  do {                                                             \
    const std::string m_ = (message);                              \
    INFO("message: " << m_);                                       \
    CHECK(m_.rfind("in.json: ", 0) == 0);                          \
    CHECK(has(m_, std::string(path) + ": "));                      \
    CHECK(has(m_, reason));                                        \
  } while (0)

inline std::string tempDir() {
  auto dir = std::filesystem::temp_directory_path() / ("earc-io-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline void checkSameScenario(const earc::Scenario& a, const earc::Scenario& b) {
  CHECK(a.name == b.name);
  CHECK(a.workspace.lo == b.workspace.lo);
  CHECK(a.workspace.hi == b.workspace.hi);
  CHECK(a.resolution.translation == b.resolution.translation);
  CHECK(a.resolution.rotation == b.resolution.rotation);
  CHECK(a.resolution.joint == b.resolution.joint);
  REQUIRE(a.obstacles.size() == b.obstacles.size());
  for (std::size_t i = 0; i < a.obstacles.size(); ++i) {
    CHECK(a.obstacles[i].type == b.obstacles[i].type);
    CHECK(a.obstacles[i].center == b.obstacles[i].center);
    CHECK(a.obstacles[i].size == b.obstacles[i].size);
    CHECK(a.obstacles[i].angle == b.obstacles[i].angle);
    CHECK(a.obstacles[i].radius == b.obstacles[i].radius);
  }
  REQUIRE(a.robots.size() == b.robots.size());
  for (std::size_t i = 0; i < a.robots.size(); ++i) {
    const auto& x = a.robots[i];
    const auto& y = b.robots[i];
    CHECK(x.name == y.name);
    CHECK(x.kind == y.kind);
    CHECK(x.shape == y.shape);
    CHECK(x.radius == y.radius);
    CHECK(x.box_size == y.box_size);
    CHECK(x.base_position == y.base_position);
    CHECK(x.base_angle == y.base_angle);
    CHECK(x.links == y.links);
    CHECK(x.link_radius == y.link_radius);
    CHECK(x.joint_limits == y.joint_limits);
    CHECK(x.start == y.start);
    CHECK(x.goal == y.goal);
  }
}

}  // namespace earc::json_test
