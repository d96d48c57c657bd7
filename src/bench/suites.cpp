#include "earc/bench/suites.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>

#include "earc/bench/results_db.hpp"
#include "earc/gen/embedded_maps.hpp"
#include "earc/gen/generators.hpp"
#include "earc/gen/movingai_scen.hpp"
#include "earc/gen/placement.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/util/hash.hpp"
#include "earc/util/random.hpp"
#include "earc/validate/scenario_check.hpp"

namespace earc::bench {

namespace {

// Generation attempts before a crowded layout is reported as an error.
constexpr int kGenerationAttempts = 8;
// Stream tags that keep trial seeds and database seeds apart.
constexpr std::uint64_t kTrialStream = 0x7419;
constexpr std::uint64_t kDatabaseStream = 0xdb;
// Of the planner seeds of scenario files' trials.
constexpr std::uint64_t kFileStream = 0xf11e;

// A stable hash of a suite name: seeds must not depend on the order
// suites are listed in.
std::uint64_t nameHash(const std::string& s) { return fnv1a64(s); }

Scenario generate(const Suite& suite, int robots, std::uint64_t seed) {
  if (!suite.map.empty()) {
    std::optional<gen::GridMap> map = gen::embeddedMovingAiMap(suite.map);
    if (!map) throw std::logic_error("suite " + suite.name + ": map " + suite.map + " is not compiled in");
    gen::MovingAiSettings s;
    s.robots = robots;
    s.seed = seed;
    // A crowd suite's random problems (databases) have its file's robots.
    if (suite.crowd()) s.footprint = gen::defaultScenFootprint();
    return gen::generateMovingAi(*map, s);
  }
  if (suite.family == "arms") {
    gen::ArmSettings s;
    s.robots = robots;
    s.obstacles = suite.obstacles ? gen::defaultArmObstacles(robots) : 0;
    s.seed = seed;
    return gen::generateArms(s);
  }
  gen::MobileSettings s;
  s.robots = robots;
  s.obstacles = suite.obstacles ? gen::kDefaultMobileObstacles : 0;
  s.seed = seed;
  return gen::generateMobile(s);
}

Scenario generateRetrying(const Suite& suite, int robots, std::uint64_t seed) {
  std::string last;
  for (int attempt = 0; attempt < kGenerationAttempts; ++attempt) {
    try {
      return generate(suite, robots, attempt == 0 ? seed : splitSeed(seed, static_cast<std::uint64_t>(attempt)));
    } catch (const std::runtime_error& e) {
      last = e.what();
    }
  }
  throw std::runtime_error("no valid " + suite.name + " scenario with " + std::to_string(robots) +
                           " robots after " + std::to_string(kGenerationAttempts) + " attempts: " + last);
}

gen::GridMap suiteMap(const Suite& suite) {
  std::optional<gen::GridMap> map = gen::embeddedMovingAiMap(suite.map);
  if (!map) throw std::logic_error("suite " + suite.name + ": map " + suite.map + " is not compiled in");
  return *map;
}

gen::MovingAiScen suiteScen(const Suite& suite) {
  std::optional<gen::MovingAiScen> scen = gen::embeddedMovingAiScen(suite.scen);
  if (!scen) throw std::logic_error("suite " + suite.name + ": scenario file " + suite.scen + " is not compiled in");
  return *scen;
}

// The crowd suite of a map and its file random-1: 50 robots, then 100 to
// 200 by 50 and on by 100, as far as the file goes, and the whole file.
Suite crowdMapSuite(const std::string& map) {
  Suite s{"crowd-" + map, "mobile", true, {}, map, map + "-random-1", 0};
  s.most_robots = static_cast<int>(suiteScen(s).agents.size());
  for (int n = 50; n < s.most_robots; n += n < 200 ? 50 : 100) s.robots.push_back(n);
  s.robots.push_back(s.most_robots);
  return s;
}

}  // namespace

const std::vector<Suite>& allSuites() {
  static const std::vector<Suite> suites = {
      {"mobile", "mobile", false, {2, 4, 8, 16, 32}, "", "", 0},
      {"mobile-obst", "mobile", true, {2, 4, 8, 16, 32}, "", "", 0},
      {"arms", "arms", false, {2, 4, 8, 16}, "", "", 0},
      {"arms-obst", "arms", true, {2, 4, 8, 16}, "", "", 0},
      // A 32x32 field with 20% of its cells blocked at random, and a game
      // level of 256x257 cells: corridors one cell wide.
      {"movingai-random", "mobile", true, {2, 4, 8, 16, 32}, "random-32-32-20", "", 0},
      {"movingai-den520d", "mobile", true, {2, 4, 8, 16, 32}, "den520d", "", 0},
      // Crowds: the benchmark's own agent lists on open floor, a random
      // field, rooms joined by narrow doors, and a warehouse's aisles.
      crowdMapSuite("empty-16-16"),
      crowdMapSuite("random-32-32-20"),
      crowdMapSuite("room-32-32-4"),
      crowdMapSuite("warehouse-10-20-10-2-1"),
  };
  return suites;
}

bool suiteTakes(const Suite& suite, int robots) {
  if (suite.crowd()) return robots >= 2 && robots <= suite.most_robots;
  return std::count(suite.robots.begin(), suite.robots.end(), robots) > 0;
}

std::vector<int> suiteCounts(const Suite& suite, const std::vector<int>& asked) {
  std::vector<int> out;
  if (suite.crowd() && !asked.empty()) {
    for (int n : asked)
      if (suiteTakes(suite, n)) out.push_back(n);
  } else {
    for (int n : suite.robots)
      if (asked.empty() || std::count(asked.begin(), asked.end(), n)) out.push_back(n);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::string suiteCountsText(const Suite& suite) {
  if (suite.crowd()) return suite.name + ": 2 to " + std::to_string(suite.most_robots);
  std::string counts = suite.name + ":";
  for (std::size_t i = 0; i < suite.robots.size(); ++i) counts += (i ? ", " : " ") + std::to_string(suite.robots[i]);
  return counts;
}

const Suite& suiteByName(const std::string& name, const std::string& option) {
  std::string names;
  for (const Suite& s : allSuites()) {
    if (s.name == name) return s;
    names += (names.empty() ? "" : ", ") + s.name;
  }
  throw InputError("", option, "unknown suite '" + name + "' (" + names + ")");
}

const std::vector<std::string>& allMethods() {
  // lacam: the configuration-based crowd solver (issue 49).
  static const std::vector<std::string> methods = {"earc", "arc", "lightning", "prioritized", "coupled", "lacam"};
  return methods;
}

std::string allMethodsText() {
  std::string text;
  for (const std::string& m : allMethods()) text += (text.empty() ? "" : ", ") + m;
  return text;
}

TrialSeeds trialSeeds(const Suite& suite, int robots, int trial, std::uint64_t run_seed) {
  std::uint64_t cell = splitSeed(splitSeed(run_seed, kTrialStream) ^ nameHash(suite.name),
                                 static_cast<std::uint64_t>(robots));
  std::uint64_t scenario = splitSeed(cell, static_cast<std::uint64_t>(trial));
  return {scenario, splitSeed(scenario, 1)};
}

// The scenario of a trial, named "<suite>-<robots>-t<trial>". Generation
// that fails (too crowded) is retried with seeds derived from the first,
// so the result is still a function of the arguments (for a crowd suite,
// of robots alone: its file's first agents).
Scenario trialScenario(const Suite& suite, int robots, int trial, std::uint64_t run_seed) {
  Scenario s;
  if (suite.crowd()) {
    gen::ScenSettings settings;
    settings.robots = robots;
    s = gen::scenarioFromScen(suiteMap(suite), suiteScen(suite), settings);
  } else {
    s = generateRetrying(suite, robots, trialSeeds(suite, robots, trial, run_seed).scenario);
  }
  s.name = suite.name + "-" + std::to_string(robots) + "-t" + std::to_string(trial);
  return s;
}

std::optional<std::int64_t> suiteLowerBound(const Suite& suite, int robots) {
  if (!suite.crowd()) return std::nullopt;
  return gen::scenLowerBound(suiteMap(suite), suiteScen(suite), robots, Resolution{}.translation);
}

Scenario databaseProblem(const Suite& suite, int robots, int index, std::uint64_t seed) {
  std::uint64_t cell = splitSeed(splitSeed(seed, kDatabaseStream) ^ nameHash(suite.name),
                                 static_cast<std::uint64_t>(robots));
  Scenario s = generateRetrying(suite, robots, splitSeed(cell, static_cast<std::uint64_t>(index)));
  s.name = suite.name + "-" + std::to_string(robots) + "-db" + std::to_string(index);
  return s;
}

std::vector<std::string> resultSuiteNames() {
  std::vector<std::string> names;
  for (const Suite& s : allSuites()) names.push_back(s.name);
  names.push_back(kFilesSuite);
  return names;
}

// What a scenario's problems share with others of their kind: its JSON
// (scenarioToJson) without its name and without its robots' starts and
// goals. Hashed, it is ScenarioFile::world; its robots, without their
// names, say which E-ARC database build covers the file.
nlohmann::json scenarioWorldJson(const Scenario& scenario) {
  nlohmann::json doc = scenarioToJson(scenario);
  doc.erase("name");
  for (auto& r : doc["robots"]) {
    r.erase("start");
    r.erase("goal");
  }
  return doc;
}

std::vector<ScenarioFile> loadScenarioFiles(const std::vector<std::string>& paths) {
  std::vector<ScenarioFile> files;
  std::map<int, int> per_count;
  for (const std::string& path : paths) {
    ScenarioFile f;
    f.path = path;
    f.scenario = loadScenario(path);
    const int n = f.robots();
    if (n < 2 || n > kMaxResultsRobots)
      throw InputError(path, "", std::to_string(n) + (n == 1 ? " robot" : " robots") + ": earc-bench run takes scenarios of 2 to " +
                                     std::to_string(kMaxResultsRobots) + " robots");
    std::size_t arms = 0;
    for (const RobotSpec& r : f.scenario.robots) arms += r.kind == RobotKind::Manipulator ? 1 : 0;
    if (arms != 0 && arms != f.scenario.robots.size())
      throw InputError(path, "$.robots",
                       "mixes mobile robots and arms: earc-bench run takes one kind per scenario (its E-ARC "
                       "databases are per kind)");
    f.family = arms ? "arms" : "mobile";
    f.trial = per_count[n]++;
    f.hash = fnv1a64(scenarioToJson(f.scenario).dump());
    f.world = fnv1a64(scenarioWorldJson(f.scenario).dump());
    files.push_back(std::move(f));
  }
  return files;
}

TrialSeeds fileTrialSeeds(const ScenarioFile& file, std::uint64_t run_seed) {
  return {file.hash, splitSeed(splitSeed(run_seed, kFileStream) ^ file.hash, 1)};
}

Scenario fileDatabaseProblem(const ScenarioFile& file, int index, std::uint64_t seed) {
  const std::uint64_t world = splitSeed(splitSeed(seed, kDatabaseStream) ^ file.world, kFileStream);
  Scenario s = gen::redrawStartsAndGoals(file.scenario, splitSeed(world, static_cast<std::uint64_t>(index)));
  s.name = std::string(kFilesSuite) + "-" + std::to_string(file.robots()) + "-db" + std::to_string(index);
  return s;
}

std::vector<std::string> splitList(const std::string& list) {
  std::vector<std::string> out;
  std::size_t from = 0;
  while (from <= list.size()) {
    std::size_t comma = list.find(',', from);
    if (comma == std::string::npos) comma = list.size();
    if (comma > from) out.push_back(list.substr(from, comma - from));
    from = comma + 1;
  }
  return out;
}

}  // namespace earc::bench
