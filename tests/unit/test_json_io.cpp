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

namespace {

json validScenario() {
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
std::string scenarioError(const json& doc) {
  try {
    earc::scenarioFromJson(doc, "in.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string geometryError(const json& doc) {
  try {
    earc::checkScenarioGeometry(earc::scenarioFromJson(doc, "in.json"), "in.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string parseError(const std::string& text) {
  try {
    earc::parseJsonText(text, "in.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Checks that the error names the file, the path and the reason.
#define CHECK_ERROR(message, path, reason)                         \
  do {                                                             \
    const std::string m_ = (message);                              \
    INFO("message: " << m_);                                       \
    CHECK(m_.rfind("in.json: ", 0) == 0);                          \
    CHECK(has(m_, std::string(path) + ": "));                      \
    CHECK(has(m_, reason));                                        \
  } while (0)

std::string tempDir() {
  auto dir = std::filesystem::temp_directory_path() / ("earc-io-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir.string();
}

void checkSameScenario(const earc::Scenario& a, const earc::Scenario& b) {
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

}  // namespace

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

// The warnings reading doc gives, as "PATH: REASON" (the file is in.json).
std::vector<std::string> ioScenarioWarnings(const json& doc) {
  earc::InputWarnings warnings;
  earc::scenarioFromJson(doc, "in.json", &warnings);
  std::vector<std::string> out;
  for (const earc::InputWarning& w : warnings) {
    CHECK(w.file == "in.json");
    out.push_back(w.where + ": " + w.reason);
  }
  return out;
}

TEST_CASE("unknown keys are read past with a warning each, a near miss suggested") {
  CHECK(ioScenarioWarnings(validScenario()).empty());
  json doc = validScenario();
  doc["obstacles"][0]["angel"] = 0.5;
  doc["obstacles"][0].erase("angle");
  doc["resolution"] = {{"translaton", 0.1}};
  doc["workspace"]["Max"] = {1, 1};
  doc["robots"][0]["comment"] = "the first";
  const auto w = ioScenarioWarnings(doc);
  // Object keys come in order (nlohmann keeps them sorted).
  REQUIRE(w.size() == 4);
  CHECK(w[0] == "$.workspace.Max: unknown key, ignored (did you mean \"max\"?)");
  CHECK(w[1] == "$.resolution.translaton: unknown key, ignored (did you mean \"translation\"?)");
  CHECK(w[2] == "$.obstacles[0].angel: unknown key, ignored (did you mean \"angle\"?)");
  CHECK(w[3] == "$.robots[0].comment: unknown key, ignored");
  // Still read, with the contract's defaults where the key was misspelt.
  earc::InputWarnings warnings;
  const earc::Scenario s = earc::scenarioFromJson(doc, "in.json", &warnings);
  CHECK(s.obstacles[0].angle == 0.0);
  CHECK(s.resolution.translation == 0.05);
}

TEST_CASE("a file's warnings stop at twenty, the rest counted in one more line") {
  json doc = validScenario();
  for (int i = 0; i < 30; ++i) doc["extra" + std::to_string(i)] = i;
  doc["robots"][0][std::string(100000, 'g')] = 1;  // long: no near miss worth measuring
  earc::InputWarnings warnings;
  earc::scenarioFromJson(doc, "in.json", &warnings);
  REQUIRE(warnings.size() == 21);
  CHECK(warnings[19].text() == "in.json: $.extra26: unknown key, ignored");  // sorted: extra0, 1, 10..19, 2, 20..
  CHECK(warnings[20].text() == "in.json: 11 more warnings like these, not shown");
}

TEST_CASE("a key of another kind of robot, shape or obstacle is said to be that kind's") {
  json doc = validScenario();
  doc["robots"][2]["shape"] = {{"type", "disc"}, {"radius", 0.3}};
  doc["robots"][0]["links"] = {1, 1};
  doc["robots"][0]["shape"]["size"] = {1, 1};
  doc["robots"][1]["shape"]["radius"] = 1;
  doc["obstacles"][0]["radius"] = 1;
  doc["obstacles"][1]["angle"] = 1;
  const auto w = ioScenarioWarnings(doc);
  REQUIRE(w.size() == 6);
  CHECK(w[0] == "$.obstacles[0].radius: a circle's key, ignored on a box");
  CHECK(w[1] == "$.obstacles[1].angle: a box's key, ignored on a circle");
  CHECK(w[2] == "$.robots[0].links: a manipulator's key, ignored on a mobile robot");
  CHECK(w[3] == "$.robots[0].shape.size: a box shape's key, ignored on a disc");
  CHECK(w[4] == "$.robots[1].shape.radius: a disc shape's key, ignored on a box shape");
  CHECK(w[5] == "$.robots[2].shape: a mobile robot's key, ignored on a manipulator");
}

TEST_CASE("an angle beyond a full turn is read, with a warning that it looks like degrees") {
  json doc = validScenario();
  doc["robots"][0]["goal"][2] = 90;
  doc["robots"][1]["start"][2] = -270;
  doc["robots"][2]["base"][2] = 180;
  doc["obstacles"][0]["angle"] = 45;
  const auto w = ioScenarioWarnings(doc);
  REQUIRE(w.size() == 4);
  CHECK(w[0] == "$.obstacles[0].angle: angle 45 is more than a full turn: angles are in radians, and this looks "
                "like degrees (45 degrees is 0.785398 rad)");
  CHECK(w[1] == "$.robots[0].goal[2]: heading 90 is more than a full turn: angles are in radians, and this looks "
                "like degrees (90 degrees is 1.5708 rad)");
  CHECK(has(w[2], "$.robots[1].start[2]: heading -270 is more than a full turn"));
  CHECK(has(w[3], "$.robots[2].base[2]: base angle 180 is more than a full turn"));
  // Still read as given (the contract allows any finite angle).
  earc::InputWarnings warnings;
  CHECK(earc::scenarioFromJson(doc, "in.json", &warnings).robots[0].goal[2] == 90);
  // A full turn, also rounded up, is no mistake.
  for (const double a : {2 * std::numbers::pi, 6.2832, -6.29, 3.15}) {
    doc = validScenario();
    doc["robots"][0]["goal"][2] = a;
    doc["obstacles"][0]["angle"] = a;
    CHECK(ioScenarioWarnings(doc).empty());
  }
}

TEST_CASE("an obstacle entirely outside the workspace is read, with a warning") {
  json doc = validScenario();  // the workspace is [0, 10] x [0, 10]
  doc["obstacles"].push_back({{"type", "circle"}, {"center", {50, 50}}, {"radius", 1}});
  // Touching the edge from outside: no robot inside can overlap it either.
  doc["obstacles"].push_back({{"type", "box"}, {"center", {-1, 5}}, {"size", {2, 2}}});
  // A corner inside: it counts.
  doc["obstacles"].push_back({{"type", "box"}, {"center", {10.5, 10.5}}, {"size", {2, 2}}, {"angle", 0.7}});
  const auto w = ioScenarioWarnings(doc);
  REQUIRE(w.size() == 2);
  CHECK(w[0] == "$.obstacles[2]: obstacle entirely outside the workspace [0, 10] x [0, 10] (it spans [49, 51] x "
                "[49, 51]): no robot can touch it; is its center right?");
  CHECK(has(w[1], "$.obstacles[3]: obstacle entirely outside the workspace"));
  earc::InputWarnings warnings;
  CHECK(earc::scenarioFromJson(doc, "in.json", &warnings).obstacles.size() == 5);
}

TEST_CASE("refused input gives its error and no warnings") {
  json doc = validScenario();
  doc["colour"] = "red";
  doc["robots"][0].erase("goal");
  earc::InputWarnings warnings;
  CHECK_THROWS_AS(earc::scenarioFromJson(doc, "in.json", &warnings), InputError);
  CHECK(warnings.empty());
  // Nor when the geometry is what is refused.
  const std::string dir = tempDir();
  doc = validScenario();
  doc["colour"] = "red";
  doc["robots"][0]["start"] = {-5, 1, 0};
  std::ofstream(dir + "/outside.json") << doc.dump();
  CHECK_THROWS_AS(earc::loadScenario(dir + "/outside.json", &warnings), InputError);
  CHECK(warnings.empty());
  doc["robots"][0]["start"] = {1, 1, 0};
  std::ofstream(dir + "/fine.json") << doc.dump();
  earc::loadScenario(dir + "/fine.json", &warnings);
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].text() == dir + "/fine.json: $.colour: unknown key, ignored");
  CHECK(earc::inputWarningLine(warnings[0], "earc-plan") ==
        "earc-plan: warning: " + dir + "/fine.json: $.colour: unknown key, ignored");
  std::filesystem::remove_all(dir);
}

TEST_CASE("a warning that quotes a key shows its control characters as '?'") {
  const earc::InputWarning w{"in.json", "$.a\nb\x1b[2J", "unknown key, ignored"};
  CHECK(earc::inputWarningLine(w, "earc-plan") == "earc-plan: warning: in.json: $.a?b?[2J: unknown key, ignored");
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

TEST_CASE("a scenario round-trips through JSON text exactly") {
  json doc = validScenario();
  doc["robots"][0]["start"] = {1.0 / 3.0, 1 + 1e-15, std::numbers::pi};
  doc["obstacles"][0]["angle"] = 0.1 + 0.2;
  doc["resolution"]["translation"] = 0.049999999999999996;
  const earc::Scenario a = earc::scenarioFromJson(doc, "in.json");
  const earc::Scenario b = earc::scenarioFromJson(earc::parseJsonText(earc::scenarioToJson(a).dump(), "x"), "x");
  checkSameScenario(a, b);
  // Defaults are written out, so a reader needs no knowledge of them.
  const json out = earc::scenarioToJson(earc::scenarioFromJson(validScenario(), "in.json"));
  CHECK(out["robots"][0]["start"][0].get<double>() == 1.0);
  CHECK(out["format"] == earc::kScenarioFormat);
}

TEST_CASE("a solution round-trips through JSON and through a file exactly") {
  earc::Solution s;
  s.scenario = "t";
  s.method = "earc";
  s.solved = true;
  s.stats = {{"planning_time_s", 0.25}, {"conflicts", 3}, {"note", "ok"}};
  earc::Path p(3);
  const double q0[] = {1.0 / 3.0, 2.0 / 7.0, -std::numbers::pi};
  const double q1[] = {0.1 + 0.2, 1e-300, 5e-324};
  p.push(q0);
  p.push(q1);
  earc::Path arm(2);
  const double r0[] = {std::nextafter(1.0, 2.0), -0.0};
  arm.push(r0);
  s.paths = {p, arm};
  s.robot_names = {"m0", "a0"};

  const earc::Solution b = earc::solutionFromJson(earc::parseJsonText(earc::solutionToJson(s).dump(), "x"), nullptr, "x");
  CHECK(b.scenario == s.scenario);
  CHECK(b.method == s.method);
  CHECK(b.solved);
  CHECK(b.stats == s.stats);
  CHECK(b.robot_names == s.robot_names);
  CHECK(b.paths == s.paths);

  const std::string dir = tempDir();
  const std::string path = dir + "/sol.json";
  earc::saveSolution(path, s);
  const earc::Solution c = earc::loadSolution(path, nullptr);
  CHECK(c.paths == s.paths);
  CHECK(c.stats == s.stats);
  CHECK(c.robot_names == s.robot_names);
  std::filesystem::remove_all(dir);
}

TEST_CASE("a solution read against its scenario checks dimensions but keeps order and unknown robots") {
  const earc::Scenario sc = earc::scenarioFromJson(validScenario(), "in.json");
  json doc = json::parse(R"({"format": "earc.solution.v1", "scenario": "t", "solved": true, "paths": [
      {"robot": "a0", "states": [[0, 0], [0.5, -0.5]]},
      {"robot": "ghost", "states": "not even states"},
      {"robot": "m0", "states": [[1, 1, 0]]}]})");
  const earc::Solution s = earc::solutionFromJson(doc, &sc, "sol.json");
  CHECK(s.robot_names == std::vector<std::string>{"a0", "ghost", "m0"});
  CHECK(s.paths[0].dim() == 2);
  CHECK(s.paths[1].empty());
  CHECK(s.paths[2].size() == 1);

  doc["paths"][0]["states"][1] = {0.5, -0.5, 0};
  try {
    earc::solutionFromJson(doc, &sc, "sol.json");
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(e.where() == "$.paths[0].states[1]");
    CHECK(has(e.reason(), "expected a state of 2 numbers"));
  }
}

TEST_CASE("a solution's own fields are checked: format, solved, paths") {
  auto error = [](const json& doc) {
    try {
      earc::solutionFromJson(doc, nullptr, "in.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  json doc = {{"format", "earc.solution.v1"}, {"solved", "yes"}, {"paths", json::array()}};
  CHECK_ERROR(error(doc), "$.solved", "expected true or false");
  doc["solved"] = true;
  doc.erase("paths");
  CHECK_ERROR(error(doc), "$.paths", "missing required field");
  doc["solved"] = false;  // an unsolved solution may leave paths out
  CHECK(error(doc).empty());
  doc["paths"] = {{{"robot", "m0"}, {"states", {{1, 2, 3}, {1, 2}}}}};
  CHECK_ERROR(error(doc), "$.paths[0].states[1]", "expected a state of 3 numbers");
  doc["paths"] = {{{"robot", "m0"}, {"states", {{1, "2", 3}}}}};
  CHECK_ERROR(error(doc), "$.paths[0].states[0][1]", "expected a number");
  doc["paths"] = {{{"states", {{1, 2, 3}}}}};
  CHECK_ERROR(error(doc), "$.paths[0].robot", "missing required field");
  doc["format"] = "earc.scenario.v1";
  CHECK_ERROR(error(doc), "$.format", "expected \"earc.solution.v1\"");
}

TEST_CASE("a solution's unknown keys are read past with a warning each; stats are free-form") {
  json doc = {{"format", "earc.solution.v1"}, {"solved", true}, {"sloved", true}, {"stats", {{"anything", 1}}},
              {"paths", {{{"robot", "m0"}, {"states", {{1, 2, 3}}}, {"colour", "red"}}}}};
  earc::InputWarnings warnings;
  const earc::Solution sol = earc::solutionFromJson(doc, nullptr, "s.json", &warnings);
  CHECK(sol.paths.size() == 1);
  REQUIRE(warnings.size() == 2);
  CHECK(warnings[0].text() == "s.json: $.sloved: unknown key, ignored (did you mean \"solved\"?)");
  CHECK(warnings[1].text() == "s.json: $.paths[0].colour: unknown key, ignored");
  doc.erase("paths");
  doc["solved"] = false;  // an unsolved solution, read as far as it goes
  warnings.clear();
  earc::solutionFromJson(doc, nullptr, "s.json", &warnings);
  CHECK(warnings.size() == 1);
}

TEST_CASE("writing a solution needs the robot names") {
  earc::Solution s;
  s.paths.emplace_back(3);
  CHECK_THROWS_AS(earc::solutionToJson(s), std::invalid_argument);
  earc::Scenario sc;
  sc.robots.resize(1);
  sc.robots[0].name = "m0";
  s.nameRobots(sc);
  CHECK(earc::solutionToJson(s)["paths"][0]["robot"] == "m0");
}

TEST_CASE("an atomic write replaces the file and leaves no temporary behind") {
  const std::string dir = tempDir();
  const std::string path = dir + "/f.txt";
  earc::writeTextFileAtomic(path, "old");
  earc::writeTextFileAtomic(path, "new text");
  CHECK(earc::readTextFile(path) == "new text");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
  CHECK(files == 1);
  CHECK_THROWS_AS(earc::writeTextFileAtomic(dir + "/no/such/dir/f.txt", "x"), std::runtime_error);
  std::filesystem::remove_all(dir);
}

TEST_CASE("the checked JSON reader builds the same document as nlohmann's parser") {
  const std::string text = R"({"a": [1, -2, 18446744073709551615, 2.5e-3, true, false, null, "s\u00e9\n"],
    "": {}, "e": [], "n": [[[], [{}]], [{"x": [{"y": {"z": [0, [1, [2]]]}}]}]], "k": {"b": 1, "a": {"c": [7]}}})";
  const json built = earc::parseJsonText(text, "in.json");
  CHECK(built == json::parse(text));
  CHECK(built.dump() == json::parse(text).dump());
  CHECK(earc::parseJsonText("42", "in.json") == json(42));
  CHECK(earc::parseJsonText("[]", "in.json") == json::array());
  // A duplicate deep inside is named by its path.
  CHECK(has(parseError(R"({"n": [[], [{"x": 1, "y": {"q": 1, "q": 2}}]]})"), "$.n[1][0].y.q: duplicate key \"q\""));
}

TEST_CASE("a file written in pieces appears whole at commit, and not at all without it") {
  const std::string dir = tempDir();
  const std::string path = dir + "/rows.jsonl";
  earc::writeTextFileAtomic(path, "old");
  {
    earc::AtomicFile file(path);
    file.write("one\n");
    file.write("two\n");
    CHECK(earc::readTextFile(path) == "old");  // nothing seen before commit
    file.commit();
  }
  CHECK(earc::readTextFile(path) == "one\ntwo\n");
  {
    earc::AtomicFile abandoned(path);  // an error on the way: never committed
    abandoned.write("half");
  }
  CHECK(earc::readTextFile(path) == "one\ntwo\n");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
  CHECK(files == 1);
  std::filesystem::remove_all(dir);
}

TEST_CASE("a process killed while writing a file atomically leaves neither the file nor a temporary") {
  const std::string dir = tempDir();
  const std::string path = dir + "/big.json";
  // Only a file system with anonymous files can promise this (elsewhere
  // the writer falls back to a named temporary).
  const int probe = ::open(dir.c_str(), O_TMPFILE | O_WRONLY, 0644);
  if (probe < 0) {
    MESSAGE("skipped: no O_TMPFILE in " << dir);
    std::filesystem::remove_all(dir);
    return;
  }
  ::close(probe);
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    // The kernel kills the writer with SIGXFSZ at 64 KiB into 1 MiB.
    const rlimit size{64 * 1024, 64 * 1024}, core{0, 0};
    ::setrlimit(RLIMIT_FSIZE, &size);
    ::setrlimit(RLIMIT_CORE, &core);
    try {
      earc::writeTextFileAtomic(path, std::string(1 << 20, 'x'));
    } catch (...) {
    }
    ::_exit(0);
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  CHECK(WIFSIGNALED(status));
  CHECK(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()) == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("two spellings of one relative path that does not exist yet are one file") {
  const std::string name = "earc-same-file-" + std::to_string(::getpid()) + ".db";
  REQUIRE_FALSE(std::filesystem::exists(name));
  CHECK(earc::sameFile(name, "./" + name));
  CHECK(earc::sameFile("./" + name, name));
  CHECK_THROWS_AS(earc::requireDistinctFiles({{"--db", name}, {"--report", "./" + name}}), InputError);
  CHECK_FALSE(earc::sameFile(name, "other-" + name));
}

TEST_CASE("makespan and sum of costs count steps, not states") {
  earc::Solution s;
  earc::Path a(1), b(1), empty(1);
  const double x = 0;
  for (int i = 0; i < 4; ++i) a.push(&x);
  b.push(&x);
  s.paths = {a, b, empty};
  CHECK(s.makespan() == 3);
  CHECK(s.sumOfCosts() == 3);
}

TEST_CASE("the project's own scenarios and solutions give no warnings") {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(earc::test::kData).parent_path().parent_path();
  earc::InputWarnings warnings;
  int files = 0;
  for (const fs::path& dir : {root / "datasets", root / "tests" / "data" / "scenarios"})
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.path().extension() != ".json") continue;
      INFO(entry.path().string());
      earc::loadScenario(entry.path().string(), &warnings);
      ++files;
    }
  for (const auto& entry : fs::directory_iterator(root / "tests" / "data" / "solutions")) {
    const std::string name = entry.path().stem().string();
    INFO(name);
    const earc::Scenario sc =
        earc::loadScenario((root / "tests" / "data" / "scenarios" / (name.substr(0, name.find("__")) + ".json")).string());
    earc::loadSolution(entry.path().string(), &sc, &warnings);
    ++files;
  }
  CHECK(files > 20);
  for (const earc::InputWarning& w : warnings) CHECK_MESSAGE(false, w.text());
  // And what the generators make, as a file would hold it.
  for (const earc::bench::Suite& suite : earc::bench::allSuites())
    for (int robots : {4, 16}) {
      const earc::Scenario s = earc::bench::trialScenario(suite, robots, 0, 1);
      INFO(s.name);
      earc::scenarioFromJson(earc::scenarioToJson(s), s.name, &warnings);
      for (const earc::InputWarning& w : warnings) CHECK_MESSAGE(false, w.text());
      warnings.clear();
    }
}
