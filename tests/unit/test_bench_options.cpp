// earc-bench's option checks, and the suites' scenarios.
#include <doctest/doctest.h>


#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <iterator>
#include <optional>
#include <set>
#include <sstream>
#include <unistd.h>

#include "earc/bench/options.hpp"
#include "earc/bench/report.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/bench/suites.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/gen/embedded_maps.hpp"
#include "earc/gen/movingai.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/cli/subcommands.hpp"

using namespace earc;
using namespace earc::bench;
#include "bench_results_fixtures.hpp"

using namespace earc::bench_test;

TEST_CASE("count and limit validators refuse 0, signs, NaN and infinities") {
  auto verdict = [](const CLI::Validator& v, std::string text) { return v(text); };
  for (const char* bad : {"0", "00", "-1", "+1", "1.5", "", "x"})
    CHECK(verdict(cli::kPositiveWholeNumber, bad) == "'" + std::string(bad) + "' is not a whole number >= 1");
  CHECK(verdict(cli::kPositiveWholeNumber, "1").empty());
  CHECK(verdict(cli::kPositiveWholeNumber, "010").empty());
  CHECK(verdict(cli::kWholeNumber, "0").empty());
  for (const char* bad : {"nan", "inf", "-inf", "x"})
    CHECK(verdict(cli::kFinitePositive, bad) == "'" + std::string(bad) + "' is not a finite number");
  CHECK(verdict(cli::kFinitePositive, "0") == "0 is not positive");
  CHECK(verdict(cli::kFiniteNonNegative, "-1") == "-1 is negative");
  CHECK(verdict(cli::kFiniteNonNegative, "0").empty());
}

TEST_CASE("an output directory may be missing or a directory, never a file (plot -o, export --ompl-log)") {
  TempPath dir("earc-out-dir");
  std::filesystem::create_directories(dir.path);
  CHECK_NOTHROW(requireOutputDirectory(dir.path, "-o"));
  CHECK_NOTHROW(requireOutputDirectory(dir.path + "/new", "-o"));
  std::ofstream(dir.path + "/a-file") << "x";
  CHECK_THROWS_WITH_AS(requireOutputDirectory(dir.path + "/a-file", "--ompl-log"),
                       (dir.path + "/a-file: --ompl-log: exists and is not a directory").c_str(), InputError);
}

TEST_CASE("option checks refuse empty items and outputs that would overwrite the input") {
  CHECK(splitOptionList("2,4", "--robots") == std::vector<std::string>{"2", "4"});
  for (const char* bad : {"2,,4", "2,", ",2", ",", ""}) CHECK_THROWS_AS(splitOptionList(bad, "--robots"), InputError);
  CHECK_THROWS_WITH(splitOptionList("2,,4", "--robots"), "--robots: empty item in '2,,4'");
  CHECK_THROWS_WITH(suiteByName("bogus", "--suite"), doctest::Contains("--suite: unknown suite 'bogus'"));

  TempPath dir("earc-same-file");
  std::filesystem::create_directories(dir.path);
  const std::string results = dir.path + "/r.sqlite";
  std::ofstream(results) << "results";
  CHECK(sameFile(results, dir.path + "/./r.sqlite"));
  CHECK(sameFile(dir.path + "/x/../new.csv", dir.path + "/new.csv"));  // neither exists
  CHECK_FALSE(sameFile(results, dir.path + "/new.csv"));
  std::filesystem::create_symlink(results, dir.path + "/link");
  CHECK(sameFile(dir.path + "/link", results));
  CHECK_THROWS_AS(requireSeparateOutputs(results, "--results", {{dir.path + "/link", "--csv"}}), InputError);
  CHECK_THROWS_AS(requireSeparateOutputs(results, "--results", {{results + "-wal", "--csv"}}), InputError);
  CHECK_THROWS_AS(requireSeparateOutputs(results, "--results",
                                         {{dir.path + "/a.csv", "--csv"}, {dir.path + "/./a.csv", "--databases-csv"}}),
                  InputError);
  CHECK_NOTHROW(requireSeparateOutputs(results, "--results",
                                       {{"", "--csv"}, {"", "--databases-csv"}, {dir.path + "/a.csv", "--x"}}));
  CHECK(lines(results) == std::vector<std::string>{"results"});  // untouched
}

TEST_CASE("a trial's scenario is a function of suite, robots, trial and seed, and databases never hold it") {
  const Suite& s = suiteByName("mobile-obst");
  CHECK(trialSeeds(s, 4, 0, 1).scenario == trialSeeds(s, 4, 0, 1).scenario);
  CHECK(trialSeeds(s, 4, 0, 1).scenario != trialSeeds(s, 4, 1, 1).scenario);
  CHECK(trialSeeds(s, 4, 0, 1).scenario != trialSeeds(suiteByName("mobile"), 4, 0, 1).scenario);
  const Scenario a = trialScenario(s, 4, 0, 1), b = trialScenario(s, 4, 0, 1);
  CHECK(a.name == "mobile-obst-4-t0");
  CHECK(a.robots.size() == 4);
  CHECK(a.obstacles.size() > 0);
  CHECK(a.robots[0].start == b.robots[0].start);
  const Scenario d = databaseProblem(s, 4, 0, 1);
  CHECK(d.robots[0].start != a.robots[0].start);
  CHECK_THROWS_AS(suiteByName("boats"), InputError);
  CHECK(splitList("a,,b,") == std::vector<std::string>{"a", "b"});
}

TEST_CASE("the MovingAI suites put robots on the compiled-in maps, which are the files in datasets/movingai") {
  // Every map in the folder is compiled in, unchanged.
  std::size_t files = 0;
  for (const auto& f : std::filesystem::directory_iterator(std::filesystem::path(EARC_SOURCE_DIR) / "datasets" / "movingai")) {
    if (f.path().extension() != ".map") continue;
    ++files;
    const gen::EmbeddedMap* m = gen::findEmbeddedMovingAiMap(f.path().stem().string());
    REQUIRE_MESSAGE(m != nullptr, f.path());
    CHECK(m->text == readTextFile(f.path().string()));
  }
  CHECK(files == gen::embeddedMovingAiMaps().size());
  CHECK(gen::findEmbeddedMovingAiMap("no-such-map") == nullptr);
  // And every scenario file.
  std::size_t scens = 0;
  for (const auto& f : std::filesystem::directory_iterator(std::filesystem::path(EARC_SOURCE_DIR) / "datasets" / "movingai")) {
    if (f.path().extension() != ".scen") continue;
    ++scens;
    const gen::EmbeddedMap* m = gen::findEmbeddedMovingAiScen(f.path().stem().string());
    REQUIRE_MESSAGE(m != nullptr, f.path());
    CHECK(m->text == readTextFile(f.path().string()));
  }
  CHECK(scens == gen::embeddedMovingAiScens().size());

  int paper = 0;
  for (const Suite& s : allSuites()) {
    paper += s.paper() ? 1 : 0;
    if (s.map.empty()) continue;
    CAPTURE(s.name);
    CHECK_FALSE(s.paper());
    CHECK(s.family == "mobile");  // E-ARC answers them from the mobile database
    const std::optional<gen::GridMap> embedded = gen::embeddedMovingAiMap(s.map);
    REQUIRE(embedded.has_value());
    const gen::GridMap& map = *embedded;
    const Scenario a = trialScenario(s, 8, 0, 1), b = trialScenario(s, 8, 0, 1), c = trialScenario(s, 8, 1, 1);
    CHECK(a.name == s.name + "-8-t0");
    CHECK(a.robots.size() == 8);
    CHECK(a.obstacles.size() == gen::mergeBlockedCells(map).size());
    CHECK(a.workspace.hi.x == map.width);
    CHECK(a.workspace.hi.y == map.height);
    for (std::size_t i = 0; i < a.robots.size(); ++i) CHECK(a.robots[i].start == b.robots[i].start);
    // A crowd suite's trials are all its file's first agents.
    if (s.crowd())
      CHECK(a.robots[0].start == c.robots[0].start);
    else
      CHECK(a.robots[0].start != c.robots[0].start);
    CHECK(databaseProblem(s, 8, 0, 1).robots[0].start != a.robots[0].start);
  }
  CHECK(paper == 4);
  CHECK(suiteByName("movingai-den520d").map == "den520d");
}
