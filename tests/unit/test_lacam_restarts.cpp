// LaCAM's restarts: a search cut short begins anew with other random
// choices, still complete, still repeatable.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/crowd_roadmap.hpp"
#include "earc/planning/lacam.hpp"
#include "support.hpp"

namespace earc {
namespace {

// The roadmap of a grid scenario's robots, all in one group.
struct RestartCase {
  explicit RestartCase(const Scenario& s)
      : sc(s), world(sc), models(sc),
        rm(world, models.raw, test::allRobots(sc), test::robotEnds(sc, true), test::robotEnds(sc, false)) {}
  Scenario sc;
  CollisionWorld world;
  RobotModels models;
  CrowdRoadmap rm;
};

TEST_CASE("LaCAM restarted after a few expansions still reaches every goal by conflict-free steps, the same way twice") {
  std::vector<std::string> rows(8, "........");
  rows[2] = "..##.#..";
  rows[5] = ".#..##..";
  const RestartCase c(test::gridScenario(rows, test::shuffledMoves(rows, 24, 7), RobotSpec::mobileDisc("", 0.3)));
  const CrowdRoadmap& rm = c.rm;
  const LacamResult plain = solveLacam(rm, Deadline(10), 3);
  REQUIRE(plain.solved);
  CHECK(plain.restarts == 0);
  REQUIRE(plain.expansions > 2);
  // A first cap under what the plain search needed: it must restart.
  const LacamResult cut = solveLacam(rm, Deadline(10), 3, 2);
  REQUIRE(cut.solved);
  CHECK(cut.restarts >= 1);
  CHECK(cut.expansions > plain.expansions);
  CHECK(test::latticeStepsConflictFree(rm, cut.configs));
  for (int i = 0; i < rm.robotCount(); ++i) {
    CHECK(cut.configs.front()[static_cast<std::size_t>(i)] == rm.start(i));
    CHECK(cut.configs.back()[static_cast<std::size_t>(i)] == rm.goal(i));
  }
  const LacamResult again = solveLacam(rm, Deadline(10), 3, 2);
  CHECK(again.configs == cut.configs);
  CHECK(again.restarts == cut.restarts);
  // A cap the plain search stays under changes nothing.
  const LacamResult roomy = solveLacam(rm, Deadline(10), 3, plain.expansions + 1);
  CHECK(roomy.restarts == 0);
  CHECK(roomy.configs == plain.configs);
}

TEST_CASE("LaCAM with restarts still proves that two robots cannot pass in a corridor without a niche") {
  const std::vector<std::string> rows = {"#######", "#.....#", "#######"};
  const RestartCase c(
      test::gridScenario(rows, {{{1.5, 1.5}, {4.5, 1.5}}, {{4.5, 1.5}, {1.5, 1.5}}}, RobotSpec::mobileDisc("", 0.3)));
  const CrowdRoadmap& rm = c.rm;
  REQUIRE(rm.problem().empty());
  const LacamResult r = solveLacam(rm, Deadline(10), 1, 1);
  CHECK_FALSE(r.solved);
  CHECK_FALSE(r.timed_out);
  CHECK(r.restarts >= 1);
  CHECK(r.why == "the roadmap has no conflict-free way to the goals");
}

}  // namespace
}  // namespace earc
