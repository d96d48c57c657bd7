// Reading and writing earc.scenario.v1 / earc.solution.v1: every kind of bad
// input is refused with a message naming the file, the JSON path and the
// reason; what is written reads back exactly.
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
#include "json_fixtures.hpp"

using namespace earc::json_test;

TEST_CASE("a well-formed scenario reads with every field in place") {
  const earc::Scenario s = earc::scenarioFromJson(validScenario(), "in.json");
  CHECK(s.name == "t");
  CHECK(s.resolution.rotation == 0.2);
  REQUIRE(s.obstacles.size() == 2);
  CHECK(s.obstacles[0].angle == 0.5);
  CHECK(s.obstacles[1].radius == 0.5);
  REQUIRE(s.robots.size() == 3);
  CHECK(s.robots[1].shape == earc::MobileShape::Box);
  CHECK(s.robots[1].box_size == earc::geo::Vec2{0.8, 0.4});
  CHECK(s.robots[2].kind == earc::RobotKind::Manipulator);
  CHECK(s.robots[2].dim() == 2);
  CHECK(s.robots[2].goal == std::vector<double>{0.5, -0.5});
  CHECK_NOTHROW(earc::checkScenarioGeometry(s, "in.json"));
}

TEST_CASE("optional scenario fields take the contract's defaults one by one") {
  json doc = validScenario();
  doc["resolution"] = {{"rotation", 0.4}};
  doc.erase("obstacles");
  doc["robots"][2].erase("joint_limits");
  doc["unknown_key"] = {{"anything", 1}};
  doc["robots"][0]["colour"] = "red";
  // Unknown keys are read past (the contract), with a warning each.
  earc::InputWarnings warnings;
  const earc::Scenario s = earc::scenarioFromJson(doc, "in.json", &warnings);
  REQUIRE(warnings.size() == 2);
  CHECK(warnings[0].text() == "in.json: $.unknown_key: unknown key, ignored");
  CHECK(warnings[1].text() == "in.json: $.robots[0].colour: unknown key, ignored");
  CHECK(s.resolution.translation == 0.05);
  CHECK(s.resolution.rotation == 0.4);
  CHECK(s.resolution.joint == 0.05);
  CHECK(s.obstacles.empty());
  REQUIRE(s.robots[2].joint_limits.size() == 2);
  CHECK(s.robots[2].joint_limits[1].first == -std::numbers::pi);
  CHECK(s.robots[2].joint_limits[1].second == std::numbers::pi);

  doc = validScenario();
  doc["obstacles"][0].erase("angle");
  CHECK(earc::scenarioFromJson(doc, "in.json").obstacles[0].angle == 0.0);
}

TEST_CASE("malformed JSON is reported with its line and column") {
  const std::string m = parseError("{\n  \"a\": [1,\n   2,, 3]\n}");
  CHECK(m.rfind("in.json: line 3, column ", 0) == 0);
  CHECK(has(m, "$.a[2]"));
  CHECK(has(m, "malformed JSON"));
  CHECK(has(parseError(""), "malformed JSON"));
  CHECK_ERROR(parseError("\xEF\xBB\xBF{}"), "line 1, column 1", "byte order mark");
}

TEST_CASE("NaN, Infinity and overflowing numbers are refused by the parser") {
  CHECK_ERROR(parseError(R"({"x": [1, NaN]})"), "line 1, column 11 ($.x[1])", "invalid literal");
  CHECK(has(parseError(R"({"x": Infinity})"), "invalid literal"));
  CHECK(has(parseError(R"({"x": -Infinity})"), "malformed JSON"));
  CHECK_ERROR(parseError(R"({"x": [0, 1e999]})"), "$.x[1]", "number overflow");
}

TEST_CASE("a syntax error's hint says what was most likely meant, and only then") {
  const std::string nan_hint = "(JSON has no NaN or Infinity; numbers must be finite)";
  for (const char* text : {R"({"x": [1, NaN]})", R"({"x": -Infinity})", R"({"x": nan})", R"({"x": inf})"}) {
    INFO(text);
    CHECK(has(parseError(text), nan_hint));
  }
  auto hinted = [&](const std::string& text, const std::string& hint) {
    const std::string m = parseError(text);
    INFO(m);
    CHECK(m.ends_with(hint));
    CHECK_FALSE(has(m, nan_hint));
  };
  hinted("// my warehouse\n{}", "(JSON has no comments)");
  hinted(R"({"a": /* x */ 1})", "(JSON has no comments)");
  hinted(R"({"a": 'x'})", "(JSON strings use double quotes)");
  hinted(R"({'a': 1})", "(JSON strings use double quotes)");
  hinted(R"({"a": 1, name: 1})", "(keys are strings in double quotes)");
  hinted(R"({"a": True})", "(JSON's literals are true, false and null, in lower case)");
  hinted("{\"a\": [1,\n  ]}", "(a trailing comma: JSON allows none before ']')");
  CHECK_ERROR(parseError("{\"a\": [1,\n  ]}"), "line 2, column 3 ($.a[1])", "unexpected ']'");
  hinted(R"({"a": 1 , })", "(a trailing comma: JSON allows none before '}')");
  // Nothing familiar: no hint.
  for (const char* text : {R"({"a": [1 2]})", R"({"a": ]})", R"({"a" 1})", R"({"a": x})", R"([{"a": 1,]])"}) {
    const std::string m = parseError(text);
    INFO(m);
    CHECK(has(m, "malformed JSON"));
    CHECK_FALSE(m.ends_with(")"));
  }
}

TEST_CASE("a duplicate key is refused with its path") {
  CHECK_ERROR(parseError(R"({"a": {"b": 1, "c": [{"d": 1, "d": 2}]}})"), "$.a.c[0].d", "duplicate key \"d\"");
  CHECK_ERROR(parseError(R"({"a": 1, "a": 1})"), "$.a", "duplicate key");
  CHECK(parseError(R"({"a": {"k": 1}, "b": {"k": 1}})").empty());  // same key in different objects
}

TEST_CASE("a missing required field is named by its path") {
  for (const char* key : {"workspace", "robots", "format"}) {
    json doc = validScenario();
    doc.erase(key);
    CHECK_ERROR(scenarioError(doc), std::string("$.") + key, "missing required field");
  }
  json doc = validScenario();
  doc["robots"][0]["shape"].erase("radius");
  CHECK_ERROR(scenarioError(doc), "$.robots[0].shape.radius", "missing required field \"radius\"");
  doc = validScenario();
  doc["robots"][2].erase("link_radius");
  CHECK_ERROR(scenarioError(doc), "$.robots[2].link_radius", "missing required field");
  doc = validScenario();
  doc["robots"][1].erase("goal");
  CHECK_ERROR(scenarioError(doc), "$.robots[1].goal", "missing required field");
  doc = validScenario();
  doc["obstacles"][1].erase("center");
  CHECK_ERROR(scenarioError(doc), "$.obstacles[1].center", "missing required field");
}

TEST_CASE("a missing required field names the key that looks like a misspelling of it") {
  json doc = validScenario();
  doc["robots"][1]["gaol"] = doc["robots"][1]["goal"];
  doc["robots"][1].erase("goal");
  CHECK_ERROR(scenarioError(doc), "$.robots[1].goal", "missing required field \"goal\" (found \"gaol\")");
  doc = validScenario();
  doc["robot"] = doc["robots"];
  doc.erase("robots");
  CHECK_ERROR(scenarioError(doc), "$.robots", "missing required field \"robots\" (found \"robot\")");
  doc = validScenario();
  doc["robots"][0]["shape"]["Radius"] = 0.3;
  doc["robots"][0]["shape"].erase("radius");
  CHECK_ERROR(scenarioError(doc), "$.robots[0].shape.radius", "(found \"Radius\")");
  // "max" is no misspelling of "min": nothing found.
  doc = validScenario();
  doc["workspace"].erase("min");
  const std::string m = scenarioError(doc);
  CHECK_ERROR(m, "$.workspace.min", "missing required field \"min\"");
  CHECK_FALSE(has(m, "found"));
}

TEST_CASE("a value of the wrong type is named with what was expected") {
  json doc = validScenario();
  doc["robots"][0]["shape"]["radius"] = "0.3";
  CHECK_ERROR(scenarioError(doc), "$.robots[0].shape.radius", "expected a number, got the string \"0.3\"");
  doc = validScenario();
  doc["robots"] = json::object();
  CHECK_ERROR(scenarioError(doc), "$.robots", "expected an array");
  doc = validScenario();
  doc["robots"][1]["name"] = 7;
  CHECK_ERROR(scenarioError(doc), "$.robots[1].name", "expected a string");
  doc = validScenario();
  doc["robots"][0]["start"][2] = true;
  CHECK_ERROR(scenarioError(doc), "$.robots[0].start[2]", "expected a number, got true");
  doc = validScenario();
  doc["workspace"]["min"] = {0, 0, 0};
  CHECK_ERROR(scenarioError(doc), "$.workspace.min", "expected an array of 2 numbers, got 3");
  doc = validScenario();
  doc["format"] = "earc.scenario.v2";
  CHECK_ERROR(scenarioError(doc), "$.format", "expected \"earc.scenario.v1\"");
  CHECK_ERROR(scenarioError(json::array()), "$", "expected an object");
}

TEST_CASE("a non-finite number in a document built in memory is refused") {
  json doc = validScenario();
  doc["robots"][0]["goal"][1] = std::nan("");
  CHECK_ERROR(scenarioError(doc), "$.robots[0].goal[1]", "not a finite number");
  doc = validScenario();
  doc["obstacles"][0]["angle"] = HUGE_VAL;
  CHECK_ERROR(scenarioError(doc), "$.obstacles[0].angle", "not a finite number");
}

TEST_CASE("sizes must be positive and the workspace non-empty") {
  struct Case {
    const char* pointer;
    json value;
    const char* path;
    const char* reason;
  };
  const Case cases[] = {
      {"/workspace/max/0", 0, "$.workspace", "min must be below max"},
      {"/workspace/min/1", 10, "$.workspace", "min must be below max"},
      {"/resolution/translation", 0, "$.resolution.translation", "must be > 0, got 0"},
      {"/resolution/joint", -0.1, "$.resolution.joint", "must be > 0, got -0.1"},
      {"/obstacles/0/size/1", 0, "$.obstacles[0].size[1]", "must be > 0, got 0"},
      {"/obstacles/1/radius", -1, "$.obstacles[1].radius", "must be > 0, got -1"},
      {"/robots/0/shape/radius", 0, "$.robots[0].shape.radius", "must be > 0"},
      {"/robots/1/shape/size/0", -0.8, "$.robots[1].shape.size[0]", "must be > 0"},
      {"/robots/2/links/1", 0, "$.robots[2].links[1]", "must be > 0"},
      {"/robots/2/link_radius", -0.1, "$.robots[2].link_radius", "must be >= 0, got -0.1"},
  };
  for (const Case& c : cases) {
    json doc = validScenario();
    doc[json::json_pointer(c.pointer)] = c.value;
    CHECK_ERROR(scenarioError(doc), c.path, c.reason);
  }
  json doc = validScenario();
  doc["robots"][2]["link_radius"] = 0;  // a zero link radius is a plain segment
  CHECK(scenarioError(doc).empty());
  doc["robots"][2]["links"] = json::array();
  CHECK_ERROR(scenarioError(doc), "$.robots[2].links", "at least one link");
}

TEST_CASE("a workspace too large to count steps across is refused naming it") {
  json doc = validScenario();
  doc["workspace"] = {{"min", {-1e9, -1e9}}, {"max", {1e9, 1e9}}};
  CHECK_ERROR(scenarioError(doc), "$.workspace", "steps across at translation resolution");
  doc["resolution"]["translation"] = 1e4;  // coarse enough: 2.8e5 steps
  CHECK(scenarioError(doc).empty());
}

TEST_CASE("a heading too large to compare modulo 2 pi is refused naming it") {
  json doc = validScenario();
  doc["robots"][1]["goal"][2] = 1e300;
  CHECK_ERROR(scenarioError(doc), "$.robots[1].goal[2]", "heading 1e+300 is beyond +-1e6 rad");
  doc = validScenario();
  doc["robots"][2]["base"][2] = -2e6;
  CHECK_ERROR(scenarioError(doc), "$.robots[2].base[2]", "beyond +-1e6 rad");
  doc = validScenario();
  doc["robots"][0]["start"][2] = 999999.0;  // many turns, but exact enough
  CHECK(scenarioError(doc).empty());
}

TEST_CASE("unknown robot, obstacle and shape types are refused") {
  json doc = validScenario();
  doc["robots"][1]["type"] = "drone";
  CHECK_ERROR(scenarioError(doc), "$.robots[1].type", "unknown robot type \"drone\"");
  doc = validScenario();
  doc["obstacles"][1]["type"] = "polygon";
  CHECK_ERROR(scenarioError(doc), "$.obstacles[1].type", "unknown obstacle type \"polygon\"");
  // An obstacle of another kind has none of a box's fields: the type is
  // what is wrong, not the missing centre (the error named "center").
  doc = validScenario();
  doc["obstacles"][1] = {{"type", "polygon"}, {"points", {{0, 0}, {1, 1}, {1, 0}}}};
  CHECK_ERROR(scenarioError(doc), "$.obstacles[1].type", "unknown obstacle type \"polygon\"");
  doc = validScenario();
  doc["robots"][0]["shape"]["type"] = "triangle";
  CHECK_ERROR(scenarioError(doc), "$.robots[0].shape.type", "unknown shape type \"triangle\"");
  // Likewise a robot of another kind without a name: the type is what is
  // wrong, not the missing name (the error named "name").
  doc = validScenario();
  doc["robots"][1] = {{"type", "drone"}, {"id", 3}};
  CHECK_ERROR(scenarioError(doc), "$.robots[1].type", "unknown robot type \"drone\"");
}

TEST_CASE("duplicate robot names are refused naming both robots") {
  json doc = validScenario();
  doc["robots"][2]["name"] = "m0";
  CHECK_ERROR(scenarioError(doc), "$.robots[2].name", "duplicate robot name \"m0\" (also $.robots[0])");
}

TEST_CASE("an empty robot name is refused") {
  json doc = validScenario();
  doc["robots"][1]["name"] = "";
  CHECK_ERROR(scenarioError(doc), "$.robots[1].name", "empty robot name");
}

TEST_CASE("an arm's start, goal and joint limits need one entry per link") {
  json doc = validScenario();
  doc["robots"][2]["start"] = {0, 0, 0};
  CHECK_ERROR(scenarioError(doc), "$.robots[2].start", "expected an array of 2 numbers (one per link), got 3");
  doc = validScenario();
  doc["robots"][2]["goal"] = {0.5};
  CHECK_ERROR(scenarioError(doc), "$.robots[2].goal", "(one per link), got 1");
  doc = validScenario();
  doc["robots"][2]["joint_limits"] = {{-1, 1}};
  CHECK_ERROR(scenarioError(doc), "$.robots[2].joint_limits", "expected 2 [lo, hi] pairs (one per link), got 1");
  doc = validScenario();
  doc["robots"][0]["start"] = {1, 1};
  CHECK_ERROR(scenarioError(doc), "$.robots[0].start", "expected an array of 3 numbers (x, y, theta), got 2");
}

TEST_CASE("joint limits with lo above hi are refused") {
  json doc = validScenario();
  doc["robots"][2]["joint_limits"][1] = {1, -1};
  CHECK_ERROR(scenarioError(doc), "$.robots[2].joint_limits[1]", "lo 1 > hi -1");
  doc["robots"][2]["joint_limits"][1] = {0, 0};  // a locked joint is fine
  doc["robots"][2]["goal"][1] = 0;
  doc["robots"][2]["start"][1] = 0;
  CHECK(scenarioError(doc).empty());
}

TEST_CASE("a start or goal outside the workspace is invalid input") {
  json doc = validScenario();
  doc["robots"][0]["start"] = {0.1, 5, 0};
  CHECK_ERROR(geometryError(doc), "$.robots[0].start", "start is outside the workspace by 0.2");
  doc = validScenario();
  doc["robots"][2]["base"] = {1, 5, 0};
  doc["robots"][2]["goal"] = {2.9, 0};  // the arm reaches over the left edge
  CHECK_ERROR(geometryError(doc), "$.robots[2].goal", "goal is outside the workspace");
}

TEST_CASE("an arm's base outside the workspace is named as the base, not the start") {
  json doc = validScenario();
  doc["robots"][2]["base"] = {-1, 5, 0};  // radius 0.1
  CHECK_ERROR(geometryError(doc), "$.robots[2].base", "base is outside the workspace by 1.1");
  // Inside by less than its link radius: the first link sticks out whatever the joints.
  doc["robots"][2]["base"] = {9.95, 5, 0};
  CHECK_ERROR(geometryError(doc), "$.robots[2].base", "base is outside the workspace by 0.05");
  // Inside, the arm reaching out is the start's fault.
  doc["robots"][2]["base"] = {9.5, 5, 0};
  CHECK_ERROR(geometryError(doc), "$.robots[2].start", "start is outside the workspace");
}

TEST_CASE("a start or goal in an obstacle names the obstacle") {
  json doc = validScenario();
  doc["robots"][0]["goal"] = {8, 2.5, 0};
  CHECK_ERROR(geometryError(doc), "$.robots[0].goal", "goal is in collision with obstacle 1 ($.obstacles[1], circle)");
  doc = validScenario();
  doc["robots"][1]["start"] = {5, 6.2, 0.3};  // rotated box corner into the rotated box
  CHECK_ERROR(geometryError(doc), "$.robots[1].start", "obstacle 0 ($.obstacles[0], box)");
}

TEST_CASE("an arm start in self-collision is invalid input") {
  json doc = validScenario();
  doc["robots"][2] = json::parse(R"({"name": "a0", "type": "manipulator", "base": [5, 8, 0],
      "links": [1, 1, 1], "link_radius": 0.1, "start": [0, 2.6, 2.6], "goal": [0, 0, 0]})");
  CHECK_ERROR(geometryError(doc), "$.robots[2].start", "start is in self-collision: a0 links 1 and 3 overlap");
}

TEST_CASE("a start or goal outside the joint limits names the joint") {
  json doc = validScenario();
  doc["robots"][2]["goal"] = {0.5, 2.5};
  CHECK_ERROR(geometryError(doc), "$.robots[2].goal[1]", "goal is outside the joint limits [-2, 2]");
  doc["robots"][2]["goal"] = {0.5, 2 + 1e-7};  // the contract's 1e-6 slack
  CHECK(geometryError(doc).empty());
  // A joint in degrees: said so, as a heading in degrees is.
  doc["robots"][2]["goal"] = {0.5, -30};
  CHECK_ERROR(geometryError(doc), "$.robots[2].goal[1]",
              "goal is outside the joint limits [-2, 2] (-30 is more than a full turn: angles are in radians, and this "
              "looks like degrees)");
  doc["robots"][2]["goal"] = {0.5, 2.5};  // just past the limit: no such hint
  CHECK_FALSE(has(geometryError(doc), "degrees"));
}

TEST_CASE("two starts or two goals that touch are invalid input") {
  json doc = validScenario();
  doc["robots"][1]["start"] = {1.5, 1, 0};
  CHECK_ERROR(geometryError(doc), "$.robots[1].start", "start touches the start of robot \"m0\" ($.robots[0])");
  doc = validScenario();
  doc["robots"][1]["goal"] = {8.45, 9, 0};  // disc r 0.3 and box half-length 0.4: 0.15 overlap
  CHECK_ERROR(geometryError(doc), "$.robots[1].goal", "goal touches the goal of robot \"m0\"");
  doc = validScenario();
  doc["robots"][1]["goal"] = {8.3, 9, 0};  // exactly touching is not overlapping
  CHECK(geometryError(doc).empty());
}

TEST_CASE("loadScenario reads, parses and checks geometry, naming the file") {
  const std::string dir = tempDir();
  const std::string path = dir + "/s.json";
  json doc = validScenario();
  doc["robots"][0]["start"] = {5, 5, 0};  // inside obstacle 0
  earc::writeTextFileAtomic(path, doc.dump());
  try {
    earc::loadScenario(path);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(e.file() == path);
    CHECK(e.where() == "$.robots[0].start");
    CHECK(has(e.reason(), "obstacle 0"));
  }
  try {
    earc::loadScenario(dir + "/missing.json");
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(has(e.what(), "missing.json: cannot open file"));
  }
  // A directory opens and reads as nothing: named as such, not as
  // malformed JSON.
  std::filesystem::create_directory(dir + "/folder.json");
  try {
    earc::loadScenario(dir + "/folder.json");
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(e.file() == dir + "/folder.json");
    CHECK(e.reason() == "is a directory, not a file");
  }
  std::filesystem::remove_all(dir);
}
