// The lattice refinement: its occupancy (who stands where at every roadmap
// step) agrees with a recount through puts and removes of robots that
// arrive at different steps, and with counted budgets it is the same run
// however loaded the machine.
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/planner.hpp"
#include "earc/planning/crowd_roadmap.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/scene/scenario.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"
#include "../../src/planning/lattice_search.hpp"

namespace earc {
namespace {

// A grid of `rows` ('#' blocked, row 0 on top) with discs of 0.3 between
// the given cells (the first start shifted by `offset`: off the lattice
// when not 0), and its crowd roadmap.
struct OccupancyWorld {
  Scenario sc;
  CollisionWorld world;
  RobotModels models;
  CrowdRoadmap rm;
  static Scenario make(const std::vector<std::string>& rows, const std::vector<std::pair<geo::Vec2, geo::Vec2>>& moves,
                       double offset) {
    Scenario sc = test::gridScenario(rows, moves, RobotSpec::mobileDisc("", 0.3));
    sc.robots.front().start[0] += offset;
    return sc;
  }
  OccupancyWorld(const std::vector<std::string>& rows, const std::vector<std::pair<geo::Vec2, geo::Vec2>>& moves,
                 double offset)
      : sc(make(rows, moves, offset)), world(sc), models(sc),
        rm(world, models.raw, test::allRobots(sc), test::robotEnds(sc, true), test::robotEnds(sc, false)) {}
};

// Random walks with no two robots on one vertex at one step, each robot
// stopping for good at a random step (so the paths end at different steps),
// trailing stays dropped.
std::vector<lattice::VertexPath> walksThatStop(const CrowdRoadmap& rm, int steps, std::mt19937_64& rng) {
  const int n = rm.robotCount();
  std::vector<lattice::VertexPath> paths(static_cast<std::size_t>(n));
  std::vector<int> stop(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    paths[static_cast<std::size_t>(i)] = {rm.start(i)};
    stop[static_cast<std::size_t>(i)] = static_cast<int>(rng() % static_cast<std::uint64_t>(steps + 1));
  }
  for (int t = 0; t < steps; ++t)
    for (int i = 0; i < n; ++i) {
      auto& p = paths[static_cast<std::size_t>(i)];
      const int here = p.back();
      if (t < stop[static_cast<std::size_t>(i)]) {
        std::vector<int> next;
        rm.placesFrom(i, here, next);
        std::shuffle(next.begin(), next.end(), rng);
        for (int v : next) {
          bool taken = false;
          for (int j = 0; j < n; ++j) taken = taken || (j != i && paths[static_cast<std::size_t>(j)].back() == v);
          if (!taken) {
            p.push_back(v);
            break;
          }
        }
      }
      if (static_cast<int>(p.size()) < t + 2) p.push_back(here);
    }
  for (auto& p : paths)
    while (p.size() > 1 && p[p.size() - 2] == p.back()) p.pop_back();
  return paths;
}

}  // namespace

TEST_CASE("The lattice occupancy agrees with a recount of its robots through puts and removes, robots parked for good") {
  const std::vector<std::string> rows = {"......", ".#....", "......", "...#..", "......", "......"};
  const std::vector<std::pair<geo::Vec2, geo::Vec2>> moves = {
      {{0.5, 0.5}, {5.5, 5.5}}, {{2.5, 0.5}, {0.5, 5.5}}, {{4.5, 1.5}, {1.5, 3.5}}, {{0.5, 3.5}, {5.5, 0.5}},
      {{3.5, 5.5}, {2.5, 2.5}}, {{5.5, 3.5}, {3.5, 0.5}}, {{1.5, 1.5}, {4.5, 4.5}}};
  for (const double offset : {0.0, 0.25}) {
    CAPTURE(offset);
    const OccupancyWorld w(rows, moves, offset);
    const CrowdRoadmap& rm = w.rm;
    const int n = rm.robotCount();
    std::mt19937_64 rng(11);
    int checks = 0, parked_blocks = 0, blocks = 0;
    for (int round = 0; round < 4; ++round) {
      std::vector<lattice::VertexPath> paths = walksThatStop(rm, 14, rng);
      std::size_t longest = 0;
      for (const auto& p : paths) longest = std::max(longest, p.size());
      lattice::Occupancy occ(rm, paths);
      CHECK(occ.horizon() == longest);
      std::vector<char> in(static_cast<std::size_t>(n), 1);
      for (int change = 0; change < 12; ++change) {
        // A robot taken out or put back, as the refinement does with a group.
        const int r = static_cast<int>(rng() % static_cast<std::uint64_t>(n));
        if (in[static_cast<std::size_t>(r)])
          occ.remove(r);
        else
          occ.put(r);
        in[static_cast<std::size_t>(r)] ^= 1;
        for (std::size_t t = 0; t < longest + 3; ++t) {
          for (int v = 0; v < rm.vertexCount(); ++v) {
            int truth = -1;
            for (int j = 0; j < n; ++j)
              if (in[static_cast<std::size_t>(j)] && lattice::vertexAt(paths[static_cast<std::size_t>(j)], t) == v) truth = j;
            CHECK(occ.at(v, t) == truth);
          }
          for (int i = 0; i < n; ++i) {
            const int u = lattice::vertexAt(paths[static_cast<std::size_t>(i)], t);
            std::vector<int> next;
            rm.placesFrom(i, u, next);
            for (int v : next) {
              bool truth = false, by_parked = false;
              for (int j = 0; j < n; ++j) {
                if (j == i || !in[static_cast<std::size_t>(j)]) continue;
                const auto& pj = paths[static_cast<std::size_t>(j)];
                if (rm.conflict(i, {u, v}, j, {lattice::vertexAt(pj, t), lattice::vertexAt(pj, t + 1)})) {
                  truth = true;
                  by_parked = by_parked || t + 1 >= pj.size();
                }
              }
              CHECK(occ.blocked(i, u, v, t) == truth);
              blocks += truth;
              parked_blocks += by_parked;
              ++checks;
            }
          }
        }
      }
    }
    // Robots parked at their goals block steps often enough for the
    // recount to mean something.
    CHECK(blocks > checks / 40);
    CHECK(parked_blocks > checks / 100);
  }
}

TEST_CASE("With counted budgets the lattice refinement is the same run twice, and its share is counted as work") {
  // A crowded 8 x 8 grid: 30 robots to their mirrored cells.
  std::vector<std::string> rows(8, "........");
  rows[2] = "..##....";
  rows[5] = "....##..";
  std::vector<std::pair<geo::Vec2, geo::Vec2>> moves;
  for (int r = 0; r < 8 && moves.size() < 30; ++r)
    for (int c = 0; c < 8 && moves.size() < 30; ++c) {
      const int rr = 7 - r, mc = 7 - c;
      if (rows[static_cast<std::size_t>(rr)][static_cast<std::size_t>(c)] == '.' &&
          rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(mc)] == '.')
        moves.push_back({{c + 0.5, r + 0.5}, {mc + 0.5, 7 - r + 0.5}});
    }
  const OccupancyWorld w(rows, moves, 0.0);
  PlannerSettings s;
  s.method = Method::Lacam;
  s.time_limit_s = 60;
  s.seed = 3;
  s.work_budgets = true;
  s.post.refine_s = 0.4;
  const PlanResult a = plan(w.sc, s);
  const PlanResult b = plan(w.sc, s);
  REQUIRE(a.solution.solved);
  REQUIRE(b.solution.solved);
  CHECK(validateSolution(w.sc, a.solution).valid);
  REQUIRE(a.stats.lacam->lattice_refine.has_value());
  const LatticeRefineStats& la = *a.stats.lacam->lattice_refine;
  const LatticeRefineStats& lb = *b.stats.lacam->lattice_refine;
  CHECK(la.neighbourhoods > 100);
  CHECK(la.neighbourhoods == lb.neighbourhoods);
  CHECK(la.expansions == lb.expansions);
  // Its cost history counts work too: the same points, at the same times.
  REQUIRE(la.history.has_value());
  REQUIRE(lb.history.has_value());
  REQUIRE(la.history->size() == lb.history->size());
  for (std::size_t k = 0; k < la.history->size(); ++k) {
    CHECK((*la.history)[k].s == (*lb.history)[k].s);
    CHECK((*la.history)[k].sum_of_costs == (*lb.history)[k].sum_of_costs);
  }
  CHECK(la.history->back().s <= *la.work_s);
  // The lattice's share of the budget, counted as work (95% on a grid).
  REQUIRE(la.work_s.has_value());
  CHECK(*la.work_s >= 0.95 * 0.4);
  CHECK(*la.work_s < 0.95 * 0.4 + 0.01);
  CHECK(*a.stats.sum_of_costs == *b.stats.sum_of_costs);
  REQUIRE(a.solution.paths.size() == b.solution.paths.size());
  for (std::size_t r = 0; r < a.solution.paths.size(); ++r) CHECK(a.solution.paths[r] == b.solution.paths[r]);
}

}  // namespace earc
