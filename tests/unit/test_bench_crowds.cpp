// The crowd suites: their counts, scenarios and lower bounds, the refine
// stats a trial records, and the crowd table.
#include <doctest/doctest.h>

#include <cstdlib>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "earc/bench/crowds.hpp"
#include "earc/bench/suites.hpp"
#include "earc/gen/embedded_maps.hpp"
#include "earc/gen/movingai_scen.hpp"

using namespace earc;
using namespace earc::bench;

TEST_CASE("the crowd suites grow to their files' agents and take any count up to them") {
  const Suite& empty = suiteByName("crowd-empty-16-16");
  CHECK(empty.crowd());
  CHECK(empty.map == "empty-16-16");
  CHECK(empty.scen == "empty-16-16-random-1");
  CHECK(empty.most_robots == 128);
  CHECK(empty.robots == std::vector<int>{50, 100, 128});
  CHECK(suiteByName("crowd-random-32-32-20").robots == std::vector<int>{50, 100, 150, 200, 300, 400, 409});
  CHECK(suiteByName("crowd-warehouse-10-20-10-2-1").robots.back() == 1000);
  CHECK(suiteTakes(empty, 4));
  CHECK_FALSE(suiteTakes(empty, 129));
  CHECK_FALSE(suiteTakes(suiteByName("mobile"), 3));
  CHECK(suiteCounts(empty, {8, 4, 500}) == std::vector<int>{4, 8});
  CHECK(suiteCounts(empty, {}) == empty.robots);
  CHECK(suiteCounts(suiteByName("mobile"), {8, 3, 2}) == std::vector<int>{2, 8});
  CHECK(suiteCountsText(empty) == "crowd-empty-16-16: 2 to 128");
  CHECK(suiteCountsText(suiteByName("arms")) == "arms: 2, 4, 8, 16");
  CHECK_FALSE(suiteLowerBound(suiteByName("mobile"), 4));
}

TEST_CASE("a crowd trial's scenario is its file's first agents, and its lower bound theirs") {
  const Suite& s = suiteByName("crowd-empty-16-16");
  const Scenario a = trialScenario(s, 8, 0, 1), b = trialScenario(s, 8, 1, 99);
  CHECK(a.name == "crowd-empty-16-16-8-t0");
  REQUIRE(a.robots.size() == 8);
  CHECK(a.robots[3].start == b.robots[3].start);
  // Line 2 of the file: start (8, 13), goal (7, 8) on a 16 x 16 map.
  CHECK(a.robots[0].start == std::vector<double>{8.5, 2.5, 0.0});
  CHECK(a.robots[0].goal == std::vector<double>{7.5, 7.5, 0.0});
  CHECK(a.robots[0].shape == MobileShape::Disc);
  // On the empty map the grid distance is the Manhattan distance.
  const auto scen = gen::embeddedMovingAiScen("empty-16-16-random-1");
  REQUIRE(scen);
  std::int64_t moves = 0;
  for (int i = 0; i < 8; ++i) {
    const gen::ScenAgent& g = scen->agents[static_cast<std::size_t>(i)];
    moves += std::abs(g.start_col - g.goal_col) + std::abs(g.start_row - g.goal_row);
  }
  CHECK(suiteLowerBound(s, 8) == moves * 20);
}

TEST_CASE("refine stats are read when a solution has them") {
  TrialRecord t;
  readRefineStats(nlohmann::json::parse(R"({"sum_of_costs": 90})"), t);
  CHECK_FALSE(t.refine_final_sum_of_costs);
  readRefineStats(nlohmann::json::parse(R"({"refine": {"first_s": 0.5, "first_sum_of_costs": 120,
      "final_sum_of_costs": 90, "final_makespan": 40}})"), t);
  CHECK(t.refine_first_time_s == 0.5);
  CHECK(t.refine_first_sum_of_costs == 120);
  CHECK(t.refine_final_sum_of_costs == 90);
  CHECK(t.refine_final_makespan == 40);
  CHECK_FALSE(t.lower_bound);
  // A suite without a bound of its own takes refinement's; a crowd
  // suite's grid bound stays.
  const auto with_bound = nlohmann::json::parse(R"({"refine": {"final_sum_of_costs": 90, "lower_bound": 70}})");
  readRefineStats(with_bound, t);
  CHECK(t.lower_bound == 70);
  t.lower_bound = 80;
  readRefineStats(with_bound, t);
  CHECK(t.lower_bound == 80);
  TrialRecord u;
  readRefineStats(nlohmann::json::parse(R"({"refine": {"first_s": -1, "final_sum_of_costs": 2.5}})"), u);
  CHECK_FALSE(u.refine_first_time_s);
  CHECK_FALSE(u.refine_final_sum_of_costs);
}

TEST_CASE("the crowd table divides the first plan's sum of costs by the lower bound") {
  auto trial = [](const std::string& method, int robots, bool ok, std::int64_t soc) {
    TrialRecord t;
    t.suite = "crowd-empty-16-16";
    t.robots = robots;
    t.method = method;
    t.time_limit_s = 10;
    t.success = ok;
    t.planning_time_s = 0.25;
    t.lower_bound = 400;
    if (ok) {
      t.sum_of_costs = soc;
      t.makespan = 70;
    } else {
      t.failure = "not solved";
    }
    return t;
  };
  TrialRecord other = trial("arc", 4, true, 500);
  other.suite = "mobile";
  CHECK(crowdTable({other}).empty());
  std::vector<TrialRecord> ts = {trial("prioritized", 4, true, 600), trial("arc", 4, true, 500),
                                 trial("arc", 8, false, 0), other};
  const std::string table = crowdTable(ts);
  CAPTURE(table);
  CHECK(table.find("### Crowds: crowd-empty-16-16 (empty-16-16-random-1.scen)") != std::string::npos);
  CHECK(table.find("| robots | method | solved | time to first solution (s) | sum of costs | makespan | lower bound | "
                   "sum of costs / lower bound |") != std::string::npos);
  // arc before prioritized (allMethods' order), counts ascending.
  CHECK(table.find("| 4 | arc | 1/1 | 0.25 | 500 | 70 | 400 | 1.25 |") < table.find("| 4 | prioritized | 1/1"));
  CHECK(table.find("| 8 | arc | 0/1 | - | - | - | 400 | - |") != std::string::npos);
  CHECK(table.find("refined") == std::string::npos);
  ts[1].refine_first_sum_of_costs = 560;
  ts[1].refine_final_sum_of_costs = 440;
  ts[1].refine_first_time_s = 0.125;
  const std::string refined = crowdTable(ts);
  CAPTURE(refined);
  CHECK(refined.find("| 4 | arc | 1/1 | 0.125 | 560 | 70 | 400 | 1.40 | 440 | 1.10 |") != std::string::npos);
}
