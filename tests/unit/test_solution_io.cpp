// Scenarios and solutions written and read back exactly, solutions' own
// fields checked, and files written whole or not at all.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>
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

TEST_CASE("numbers are written with the fewest digits that read back, laid out as nlohmann prints them") {
  const auto text = [](double v) {
    std::string out;
    earc::appendJsonDouble(out, v);
    return out;
  };
  for (double v : {0.0, -0.0, 2.0, -3.0, 0.05, 12.5, -1.25, 0.1 + 0.2, 1.0 / 3.0, 1e-4, 1e-5, 1e-7, 123.456e-9, 1e15,
                   1e16, 123456789012345.0, 1e21, 1.5e300, -2.5e-300, 5e-324, std::numbers::pi})
    CHECK_MESSAGE(text(v) == json(v).dump(), v);
  CHECK(text(std::nan("")) == "null");
  CHECK(text(-HUGE_VAL) == "null");
  // Any bit pattern reads back bitwise, never longer than nlohmann's text.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> near(-100.0, 100.0);
  for (int i = 0; i < 200000; ++i) {
    std::uint64_t bits = rng();
    double v;
    std::memcpy(&v, &bits, sizeof v);
    if (i % 2) v = near(rng);
    if (!std::isfinite(v)) continue;
    const std::string t = text(v);
    const double back = json::parse(t).get<double>();
    REQUIRE_MESSAGE(std::memcmp(&back, &v, sizeof v) == 0, t);
    REQUIRE(t.size() <= json(v).dump().size());
  }
}

TEST_CASE("a saved solution's states are laid out one per line") {
  earc::Solution s;
  s.scenario = "t";
  s.solved = true;
  earc::Path p(3);
  const double q0[] = {0.0, 2.5, -1.25};
  const double q1[] = {1e-7, 12.0, 0.05};
  p.push(q0);
  p.push(q1);
  s.paths = {p, earc::Path(2)};
  s.robot_names = {"m0", "a0"};
  const std::string dir = tempDir();
  earc::saveSolution(dir + "/sol.json", s);
  const std::string t = earc::readTextFile(dir + "/sol.json");
  CHECK(t.find("\"states\": [\n      [0.0,2.5,-1.25],\n      [1e-07,12.0,0.05]\n    ]}") != std::string::npos);
  CHECK(t.find("{\"robot\": \"a0\", \"states\": []}") != std::string::npos);
  CHECK(json::parse(t) == earc::solutionToJson(s));
  s.robot_names.pop_back();
  CHECK_THROWS_AS(earc::saveSolution(dir + "/sol.json", s), std::invalid_argument);
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
