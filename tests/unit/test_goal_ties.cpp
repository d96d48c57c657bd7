// The lattice searches' avoid_goals: among equally short ways, the one off
// another robot's goal before that robot arrives.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/crowd_roadmap.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/scene/scenario.hpp"
#include "support.hpp"
#include "../../src/planning/lattice_search.hpp"
#include "../../src/planning/tick_search.hpp"

namespace earc {
namespace goal_ties {

// Five cells by three round a wall cell: robot 0 from the middle row's
// left end to the cell right of the wall has two equally short ways (over
// and under it; no diagonal, the wall breaks both squares). Robot 1 waits
// at the bottom right and then goes to its goal, the cell over (top) or
// under the wall, arriving long after robot 0 would pass there.
struct Ring {
  Scenario sc;
  CollisionWorld world;
  RobotModels models;
  CrowdRoadmap rm;
  explicit Ring(bool top)
      : sc(test::gridScenario({".....", ".#...", "....."},
                              {{{0.5, 1.5}, {2.5, 1.5}}, {{4.5, 0.5}, {1.5, top ? 2.5 : 0.5}}},
                              RobotSpec::mobileDisc("", 0.3))),
        world(sc),
        models(sc),
        rm(world, models.raw, test::allRobots(sc), test::robotEnds(sc, true), test::robotEnds(sc, false)) {}
  int cell(double x, double y) const {
    for (int v = 0; v < rm.vertexCount(); ++v)
      if (std::abs(rm.position(v).x - x) < 1e-9 && std::abs(rm.position(v).y - y) < 1e-9) return v;
    return -1;
  }
  // Robot 1's way: ten steps at its start, then along the right column and
  // the top (or bottom) row to its goal.
  lattice::VertexPath secondWay(bool top) const {
    lattice::VertexPath p(11, cell(4.5, 0.5));
    const std::vector<std::pair<double, double>> route =
        top ? std::vector<std::pair<double, double>>{{4.5, 1.5}, {4.5, 2.5}, {3.5, 2.5}, {2.5, 2.5}, {1.5, 2.5}}
            : std::vector<std::pair<double, double>>{{3.5, 0.5}, {2.5, 0.5}, {1.5, 0.5}};
    for (const auto& [x, y] : route) p.push_back(cell(x, y));
    return p;
  }
};

}  // namespace goal_ties

TEST_CASE("With avoid_goals the lattice searches take the equally short way off a goal not yet reached") {
  int plain_crossings = 0, tick_plain_crossings = 0;
  for (bool top : {true, false}) {
    CAPTURE(top);
    const goal_ties::Ring w(top);
    REQUIRE(w.rm.allOnLattice());
    const int goal1 = w.rm.goal(1);
    std::vector<lattice::VertexPath> paths = {{w.rm.start(0)}, w.secondWay(top)};
    REQUIRE(paths[1].back() == goal1);
    lattice::Occupancy occ(w.rm, paths);
    occ.remove(0);
    lattice::StepSearch search(w.rm);
    const auto plain = search.search(occ, 0, Deadline(), 100, 100000, 1.0, false);
    const auto avoid = search.search(occ, 0, Deadline(), 100, 100000, 1.0, true);
    REQUIRE(plain.has_value());
    REQUIRE(avoid.has_value());
    CHECK(avoid->size() == 5);  // four moves either way
    CHECK(plain->size() == avoid->size());
    CHECK(std::find(avoid->begin(), avoid->end(), goal1) == avoid->end());
    plain_crossings += std::find(plain->begin(), plain->end(), goal1) != plain->end();

    // The same in ticks: a step is two ticks, a move's first one between cells.
    const auto lat = ticks::Lattice::make(w.rm);
    REQUIRE(lat.has_value());
    std::vector<ticks::TickPath> tpaths(2);
    tpaths[0] = {w.rm.start(0)};
    tpaths[1] = {paths[1].front()};
    for (std::size_t t = 1; t < paths[1].size(); ++t) {
      tpaths[1].push_back(paths[1][t] == paths[1][t - 1] ? paths[1][t] : -1);
      tpaths[1].push_back(paths[1][t]);
    }
    ticks::Occupancy tocc(*lat, tpaths);
    tocc.remove(0);
    ticks::TickSearch tsearch(*lat);
    const auto tplain = tsearch.search(tocc, 0, Deadline(), 100, 100000, 1.0, false);
    const auto tavoid = tsearch.search(tocc, 0, Deadline(), 100, 100000, 1.0, true);
    REQUIRE(tplain.has_value());
    REQUIRE(tavoid.has_value());
    CHECK(tavoid->size() == 9);  // four axis moves of two ticks
    CHECK(std::find(tavoid->begin(), tavoid->end(), goal1) == tavoid->end());
    tick_plain_crossings += std::find(tplain->begin(), tplain->end(), goal1) != tplain->end();
  }
  // Without it the searches break the tie the same way in both worlds:
  // through robot 1's goal in one of them.
  CHECK(plain_crossings == 1);
  CHECK(tick_plain_crossings == 1);
}

}  // namespace earc
