// Input read all the same but most likely a mistake: one warning line each,
// naming the file and the JSON path.
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
#include "support.hpp"

using earc::InputError;
using nlohmann::json;
#include "json_fixtures.hpp"

using namespace earc::json_test;

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
