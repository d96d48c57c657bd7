// The crowd solver: its conflict table against the validator, LaCAM on
// instances that defeat prioritized planning, and ARC's hand-over of jams.
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "earc/methods/plan.hpp"
#include "earc/planning/crowd.hpp"
#include "earc/planning/lacam.hpp"
#include "earc/planning/lattice_lns.hpp"
#include "earc/planning/methods.hpp"
#include "earc/planning/planner.hpp"
#include "earc/util/random.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"
#include "../../src/planning/crowd_spread.hpp"
#include "../../src/planning/lattice_search.hpp"

namespace earc {
namespace {

using test::gridScenario;

// The validator's verdict on two robots stepping a -> b and c -> d over
// `steps` time steps (steps and midpoints, the contract's instants).
bool validatorSeesTouch(const Scenario& sc, geo::Vec2 a, geo::Vec2 b, geo::Vec2 c, geo::Vec2 d, int steps) {
  InstantChecker checker(sc);
  const int both[2] = {0, 1};
  for (int k = 0; k <= 2 * steps; ++k) {
    const double s = static_cast<double>(k) / (2.0 * steps);
    const double qa[3] = {a.x + (b.x - a.x) * s, a.y + (b.y - a.y) * s, 0.0};
    const double qc[3] = {c.x + (d.x - c.x) * s, c.y + (d.y - c.y) * s, 0.0};
    const double* q[2] = {qa, qc};
    std::vector<Violation> out;
    checker.checkGeometry(both, q, k * 0.5, out);
    for (const auto& v : out)
      if (v.type == Violation::Type::RobotRobot) return true;
  }
  return false;
}

// Every pair of steps of two robots among the lattice vertices of an open
// 5 x 5 grid, by the roadmap's conflict test and by the validator.
struct Agreement {
  int pairs = 0, conflicts = 0, disagreements = 0, unsafe = 0;
};
Agreement compareWithValidator(RobotSpec shape) {
  const std::vector<std::string> open(5, ".....");
  const Scenario sc = gridScenario(open, {{{0.5, 0.5}, {1.5, 0.5}}, {{4.5, 4.5}, {3.5, 4.5}}}, shape);
  const CollisionWorld world(sc);
  const RobotModels models(sc);
  const CrowdRoadmap rm(world, models.raw, {0, 1}, {sc.robots[0].start, sc.robots[1].start},
                        {sc.robots[0].goal, sc.robots[1].goal});
  Agreement a;
  for (int u = 0; u < rm.vertexCount(); ++u)
    for (int w = 0; w < rm.vertexCount(); ++w) {
      if (u == w) continue;
      std::vector<int> su = rm.neighbours(u), sw = rm.neighbours(w);
      su.push_back(u);
      sw.push_back(w);
      for (int v : su)
        for (int x : sw) {
          const bool table = rm.conflict(0, {u, v}, 1, {w, x});
          const bool valid = validatorSeesTouch(sc, rm.position(u), rm.position(v), rm.position(w), rm.position(x),
                                                rm.stepsPerEdge());
          ++a.pairs;
          a.conflicts += table;
          a.disagreements += table != valid;
          a.unsafe += !table && valid;
        }
    }
  return a;
}

PlannerSettings lacamSettings(std::uint64_t seed = 1) {
  PlannerSettings s;
  s.method = Method::Lacam;
  s.time_limit_s = 20;
  s.seed = seed;
  return s;
}

}  // namespace

TEST_CASE("closestApproach equals the smallest sampled distance of two synchronous straight motions") {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    geo::Vec2 p[4];
    for (auto& v : p) v = {uniform(rng, -2, 2), uniform(rng, -2, 2)};
    double best = 1e300;
    for (int k = 0; k <= 20000; ++k) {
      const double s = k / 20000.0;
      best = std::min(best, geo::norm((p[0] + (p[1] - p[0]) * s) - (p[2] + (p[3] - p[2]) * s)));
    }
    const double exact = closestApproach(p[0], p[1], p[2], p[3]);
    CHECK(exact <= best + 1e-12);
    CHECK(exact >= best - 1e-3);
  }
}

TEST_CASE("The crowd conflict table agrees with the validator for discs on every pair of lattice steps") {
  for (double r : {0.3, 0.36, 0.45}) {
    CAPTURE(r);
    const Agreement a = compareWithValidator(RobotSpec::mobileDisc("", r));
    CHECK(a.pairs > 5000);
    CHECK(a.conflicts > 0);
    CHECK(a.disagreements == 0);
  }
}

TEST_CASE("For boxes the crowd conflict table is a bound: every touch the validator sees is a conflict") {
  const Agreement a = compareWithValidator(RobotSpec::mobileBox("", {0.6, 0.4}));
  CHECK(a.pairs > 5000);
  CHECK(a.unsafe == 0);
  CHECK(a.disagreements > 0);  // the bounding disc takes more room than the box
}

TEST_CASE("Swapping on an edge conflicts; following into a vertex another leaves does not, unless the discs reach round the corner") {
  const std::vector<std::string> open(3, "...");
  for (double r : {0.3, 0.36}) {
    CAPTURE(r);
    const Scenario sc = gridScenario(open, {{{0.5, 0.5}, {1.5, 0.5}}, {{2.5, 2.5}, {1.5, 2.5}}}, RobotSpec::mobileDisc("", r));
    const CollisionWorld world(sc);
    const RobotModels models(sc);
    const CrowdRoadmap rm(world, models.raw, {0, 1}, {sc.robots[0].start, sc.robots[1].start},
                          {sc.robots[0].goal, sc.robots[1].goal});
    REQUIRE(rm.gridAligned());
    REQUIRE(rm.vertexCount() == 9);
    // Lattice vertex ids run row by row from the bottom left.
    auto id = [](int c, int row) { return row * 3 + c; };
    const int steps = rm.stepsPerEdge();
    auto both = [&](int u, int v, int w, int x) {
      const bool table = rm.conflict(0, {u, v}, 1, {w, x});
      CHECK(table == validatorSeesTouch(sc, rm.position(u), rm.position(v), rm.position(w), rm.position(x), steps));
      return table;
    };
    CHECK(both(id(0, 0), id(1, 0), id(1, 0), id(0, 0)));       // swap on an edge
    CHECK(both(id(0, 0), id(1, 0), id(2, 0), id(1, 0)));       // both enter one vertex
    CHECK_FALSE(both(id(0, 0), id(1, 0), id(1, 0), id(2, 0))); // following straight on
    // Following round a corner: the discs come within 0.707 of each other.
    CHECK(both(id(0, 0), id(1, 0), id(1, 0), id(1, 1)) == (2 * r > std::sqrt(0.5)));
  }
}

TEST_CASE("LaCAM swaps two robots in a corridor with one niche, where prioritized planning cannot") {
  const std::vector<std::string> rows = {"#######", "###.###", "#.....#", "#######"};
  // Corridor cells (1..5, row 2 from the top), niche above cell 3.
  const Scenario sc = gridScenario(rows, {{{2.5, 1.5}, {4.5, 1.5}}, {{4.5, 1.5}, {2.5, 1.5}}}, RobotSpec::mobileDisc("", 0.3));
  const PlanResult lacam = plan(sc, lacamSettings());
  REQUIRE(lacam.solution.solved);
  CHECK(validateSolution(sc, lacam.solution).valid);
  PlannerSettings pri;
  pri.method = Method::Prioritized;
  pri.time_limit_s = 3;
  CHECK_FALSE(plan(sc, pri).solution.solved);
}

TEST_CASE("LaCAM turns four robots round a walled 2x2 block, where every robot's next cell is taken") {
  const std::vector<std::string> rows = {"####", "#..#", "#..#", "####"};
  const geo::Vec2 c00{1.5, 1.5}, c10{2.5, 1.5}, c11{2.5, 2.5}, c01{1.5, 2.5};
  const Scenario sc = gridScenario(rows, {{c00, c10}, {c10, c11}, {c11, c01}, {c01, c00}}, RobotSpec::mobileDisc("", 0.3));
  const PlanResult r = plan(sc, lacamSettings());
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(sc, r.solution).valid);
  // One rotation of the block: a single roadmap step.
  CHECK(r.stats.lacam->roadmap_steps == 1);
}

TEST_CASE("LaCAM plans box robots off the lattice in a free-form world, and the same seed gives the same plan") {
  Scenario sc;
  sc.name = "free";
  sc.workspace = {{0, 0}, {8, 6}};
  sc.obstacles.push_back(Obstacle::makeBox({4.0, 3.0}, {1.3, 2.2}, 0.4));
  sc.obstacles.push_back(Obstacle::makeCircle({2.3, 5.2}, 0.5));
  std::mt19937_64 rng(11);
  const double headings[] = {0.0, 1.2, -2.5, 3.0, 0.7, -1.0};
  for (int i = 0; i < 6; ++i) {
    RobotSpec s = RobotSpec::mobileBox("b" + std::to_string(i), {0.6, 0.4});
    s.start = {0.6 + 0.05 * i, 0.7 + 0.8 * i, headings[i]};
    s.goal = {7.3 - 0.03 * i, 5.2 - 0.8 * i, -headings[i]};
    sc.robots.push_back(s);
  }
  const PlanResult a = plan(sc, lacamSettings(5));
  REQUIRE(a.solution.solved);
  CHECK(validateSolution(sc, a.solution).valid);
  CHECK(a.stats.lacam->grid_lattice == false);
  const PlanResult b = plan(sc, lacamSettings(5));
  REQUIRE(b.solution.solved);
  CHECK(a.solution.paths == b.solution.paths);
}

TEST_CASE("LaCAM says why when a robot's goal is walled off, and refuses arms") {
  const std::vector<std::string> rows = {".#.", ".#.", ".#."};
  const Scenario sc = gridScenario(rows, {{{0.5, 0.5}, {2.5, 0.5}}}, RobotSpec::mobileDisc("", 0.3));
  const PlanResult r = plan(sc, lacamSettings());
  CHECK_FALSE(r.solution.solved);
  CHECK(r.failures.count(FailureCause::NoIndividualPath) == 1);
  CHECK(r.stats.detail->find("robot m0") != std::string::npos);

  Scenario arms;
  arms.name = "arms";
  arms.workspace = {{0, 0}, {10, 10}};
  arms.robots.push_back(test::fiveLinkArm("a0", {5, 5}, 0, {0, 0, 0, 0, 0}, {0.3, 0, 0, 0, 0}));
  const PlanResult ra = plan(arms, lacamSettings());
  CHECK_FALSE(ra.solution.solved);
  CHECK(ra.failures.count(FailureCause::InvalidInput) == 1);
}

TEST_CASE("ARC hands a jam on a crowded grid to the crowd solver and solves it; crowd_fallback off, it hands nothing over") {
  std::vector<std::string> rows(7, ".......");
  rows[3] = "...#...";
  // 42 robots on a 7 x 7 grid, each going to the cell mirrored through the
  // centre: everyone meets in the middle. (A fleet of 32 or fewer is handed
  // over only after ARC's own levels fail: test_arc.cpp.)
  std::vector<std::pair<geo::Vec2, geo::Vec2>> moves;
  for (int r = 0; r < 7; ++r)
    for (int c = 0; c < 7; ++c)
      if (r != 3) moves.push_back({{c + 0.5, r + 0.5}, {6 - c + 0.5, 6 - r + 0.5}});
  const Scenario sc = gridScenario(rows, moves, RobotSpec::mobileDisc("", 0.3));
  PlannerSettings s;
  s.method = Method::Arc;
  s.time_limit_s = 30;
  const PlanResult r = plan(sc, s);
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(sc, r.solution).valid);
  CHECK(r.stats.arc->crowd_handovers.size() >= 1);
  // (How much longer ARC takes alone is for a benchmark, not a test.)
  s.arc.crowd_fallback = false;
  s.time_limit_s = 1;
  const PlanResult alone = plan(sc, s);
  CHECK(alone.stats.arc->crowd_handovers.empty());
  CHECK(alone.stats.arc->crowd_s == 0.0);
}

TEST_CASE("ARC with --refine shortens a jam of every robot on the crowd solver's lattice, off the first plan's clock") {
  std::vector<std::string> rows(7, ".......");
  rows[3] = "...#...";
  std::vector<std::pair<geo::Vec2, geo::Vec2>> moves;
  for (int r = 0; r < 7; ++r)
    for (int c = 0; c < 7; ++c)
      if (r != 3) moves.push_back({{c + 0.5, r + 0.5}, {6 - c + 0.5, 6 - r + 0.5}});
  const Scenario sc = gridScenario(rows, moves, RobotSpec::mobileDisc("", 0.3));
  PlannerSettings s;
  s.method = Method::Arc;
  s.time_limit_s = 30;
  s.post.refine_s = 1.0;
  const PlanResult r = plan(sc, s);
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(sc, r.solution).valid);
  REQUIRE(!r.stats.arc->crowd_handovers.empty());
  REQUIRE(r.stats.arc->crowd_handovers.back().robots == static_cast<std::int64_t>(moves.size()));
  REQUIRE(r.stats.lacam.has_value());
  REQUIRE(r.stats.lacam->lattice_refine.has_value());
  const auto& lattice = *r.stats.lacam->lattice_refine;
  CHECK(lattice.sum_of_costs_after <= lattice.sum_of_costs_before);
  REQUIRE(r.stats.refine.has_value());
  CHECK(r.stats.refine->final_sum_of_costs <= r.stats.refine->first_sum_of_costs);
  CHECK(r.stats.refine->first_sum_of_costs == *r.stats.lacam->first_sum_of_costs);
  // The first plan's time leaves the lattice refinement out; the record
  // starts at the first plan and counts the lattice run as refinement.
  CHECK(r.stats.refine->history.front().s == *r.stats.planning_time_s);
  REQUIRE(r.stats.refine->lattice_s.has_value());
  REQUIRE(lattice.s.has_value());
  CHECK(*r.stats.refine->lattice_s == *lattice.s);
  CHECK(r.stats.refine->seconds_spent >= *r.stats.refine->lattice_s);
}

}  // namespace earc

namespace earc {

TEST_CASE("Refining on the lattice never raises the sum of costs, keeps every step conflict-free, and shortens a crowded plan") {
  std::vector<std::string> rows(8, "........");
  rows[2] = "..##.#..";
  rows[5] = ".#..##..";
  const Scenario sc = gridScenario(rows, test::shuffledMoves(rows, 24, 7), RobotSpec::mobileDisc("", 0.3));
  const CollisionWorld world(sc);
  const RobotModels models(sc);
  std::vector<int> group;
  std::vector<std::vector<double>> starts, ends;
  for (int i = 0; i < 24; ++i) {
    group.push_back(i);
    starts.push_back(sc.robots[static_cast<std::size_t>(i)].start);
    ends.push_back(sc.robots[static_cast<std::size_t>(i)].goal);
  }
  const CrowdRoadmap rm(world, models.raw, group, starts, ends);
  const LacamResult first = solveLacam(rm, Deadline(10), 3);
  REQUIRE(first.solved);
  REQUIRE(test::latticeStepsConflictFree(rm, first.configs));
  const long long before = latticeSumOfCosts(rm, first.configs);
  long long last = before;
  for (int rounds : {1, 10, 200}) {
    std::vector<std::vector<int>> configs = first.configs;
    const LatticeRefineStats st = refineOnLattice(rm, configs, Deadline(), 3, rounds);
    const long long after = latticeSumOfCosts(rm, configs);
    CHECK(st.sum_of_costs_after == after);
    CHECK(after <= last);
    // The cost history: the start, then lower sums at later times, the end last.
    REQUIRE(st.history.has_value());
    const std::vector<RefinePoint>& h = *st.history;
    REQUIRE(!h.empty());
    CHECK(h.front().s == 0.0);
    CHECK(h.front().sum_of_costs == before);
    CHECK(h.back().sum_of_costs == after);
    CHECK(h.back().makespan == static_cast<std::int64_t>(configs.size()) - 1);
    for (std::size_t k = 1; k < h.size(); ++k) {
      CHECK(h[k].sum_of_costs < h[k - 1].sum_of_costs);
      CHECK(h[k].s >= h[k - 1].s);
    }
    if (after < before) CHECK(h.size() >= 2);
    last = after;
    CHECK(test::latticeStepsConflictFree(rm, configs));
    for (int i = 0; i < 24; ++i) {
      CHECK(configs.front()[static_cast<std::size_t>(i)] == rm.start(i));
      CHECK(configs.back()[static_cast<std::size_t>(i)] == rm.goal(i));
    }
  }
  CHECK(last < before);
}

TEST_CASE("One robot's search through the others' steps waits until its goal stays free, and meets no one") {
  const std::vector<std::string> rows(3, ".....");
  // Robot 0 crosses the middle row; robot 1's goal is on its way.
  const Scenario sc = gridScenario(rows, {{{0.5, 1.5}, {4.5, 1.5}}, {{2.5, 0.5}, {2.5, 1.5}}}, RobotSpec::mobileDisc("", 0.3));
  const CollisionWorld world(sc);
  const RobotModels models(sc);
  const CrowdRoadmap rm(world, models.raw, {0, 1}, {sc.robots[0].start, sc.robots[1].start},
                        {sc.robots[0].goal, sc.robots[1].goal});
  std::vector<lattice::VertexPath> paths(2);
  int v = rm.start(0);
  paths[0].push_back(v);
  while (v != rm.goal(0)) {
    for (int w : rm.neighbours(v))
      if (rm.distanceToGoal(0, w) < rm.distanceToGoal(0, v)) {
        v = w;
        break;
      }
    paths[0].push_back(v);
  }
  REQUIRE(paths[0].size() == 5);
  paths[1] = {rm.start(1)};
  lattice::Occupancy occ(rm, paths);
  occ.remove(1);
  lattice::StepSearch search(rm);
  const auto p = search.search(occ, 1, Deadline(), 16, 100000);
  REQUIRE(p.has_value());
  CHECK(p->front() == rm.start(1));
  CHECK(p->back() == rm.goal(1));
  // Robot 0 stands on robot 1's goal at step 2: one step is no longer enough.
  CHECK(p->size() - 1 == 3);
  for (std::size_t t = 0; t + 1 < std::max(p->size(), paths[0].size()) + 2; ++t)
    CHECK_FALSE(rm.conflict(1, {lattice::vertexAt(*p, t), lattice::vertexAt(*p, t + 1)}, 0,
                            {lattice::vertexAt(paths[0], t), lattice::vertexAt(paths[0], t + 1)}));
  CHECK(search.expansions() > 0);
  // No way by step 2; the greedier search finds the same way by step 3.
  CHECK_FALSE(search.search(occ, 1, Deadline(), 2, 100000).has_value());
  const auto greedy = search.search(occ, 1, Deadline(), 3, 100000, 1.5);
  REQUIRE(greedy.has_value());
  CHECK(greedy->size() - 1 == 3);
  CHECK(greedy->back() == rm.goal(1));
}

namespace {

// Random walks of the robots over rm's vertices for `steps` steps, no two
// on one vertex at one step (the occupancy keeps one robot per vertex).
std::vector<lattice::VertexPath> randomWalks(const CrowdRoadmap& rm, int steps, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const int n = rm.robotCount();
  std::vector<lattice::VertexPath> paths(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) paths[static_cast<std::size_t>(i)] = {rm.start(i)};
  for (int t = 0; t < steps; ++t)
    for (int i = 0; i < n; ++i) {
      std::vector<int> next;
      rm.placesFrom(i, paths[static_cast<std::size_t>(i)].back(), next);
      std::shuffle(next.begin(), next.end(), rng);
      for (int v : next) {
        bool taken = false;
        for (int j = 0; j < i; ++j) taken = taken || paths[static_cast<std::size_t>(j)].back() == v;
        for (int j = i + 1; j < n; ++j) taken = taken || paths[static_cast<std::size_t>(j)].back() == v;
        if (!taken) {
          paths[static_cast<std::size_t>(i)].push_back(v);
          break;
        }
      }
      if (static_cast<int>(paths[static_cast<std::size_t>(i)].size()) < t + 2)
        paths[static_cast<std::size_t>(i)].push_back(paths[static_cast<std::size_t>(i)].back());
    }
  return paths;
}

}  // namespace

TEST_CASE("The occupancy's step check agrees with the roadmap's conflict test against every robot") {
  const std::vector<std::string> rows = {"......", ".#....", "......", "...#..", "......", "......"};
  struct Case {
    const char* name;
    RobotSpec shape;
    double offset;  // of the first robot's start from its cell centre: off the lattice when not 0
  };
  for (const Case& c : {Case{"discs of 0.3", RobotSpec::mobileDisc("", 0.3), 0.0},
                        Case{"discs of 0.45", RobotSpec::mobileDisc("", 0.45), 0.0},
                        Case{"discs of 0.3, one start off the lattice", RobotSpec::mobileDisc("", 0.3), 0.25}}) {
    CAPTURE(c.name);
    const Scenario sc = gridScenario(
        rows,
        {{{0.5 + c.offset, 0.5}, {5.5, 5.5}}, {{2.5, 0.5}, {0.5, 5.5}}, {{4.5, 1.5}, {1.5, 3.5}},
         {{0.5, 3.5}, {5.5, 0.5}}, {{3.5, 5.5}, {2.5, 2.5}}, {{5.5, 3.5}, {3.5, 0.5}}},
        c.shape);
    const CollisionWorld world(sc);
    const RobotModels models(sc);
    std::vector<int> group;
    std::vector<std::vector<double>> starts, goals;
    for (std::size_t r = 0; r < sc.robots.size(); ++r) {
      group.push_back(static_cast<int>(r));
      starts.push_back(sc.robots[r].start);
      goals.push_back(sc.robots[r].goal);
    }
    const CrowdRoadmap rm(world, models.raw, group, starts, goals);
    CHECK(rm.allOnLattice() == (c.offset == 0.0));
    int blocked = 0, checks = 0;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      std::vector<lattice::VertexPath> paths = randomWalks(rm, 12, seed);
      const lattice::Occupancy occ(rm, paths);
      for (int i = 0; i < rm.robotCount(); ++i)
        for (int u = 0; u < rm.vertexCount(); ++u) {
          std::vector<int> next;
          rm.placesFrom(i, u, next);
          for (int v : next)
            for (std::size_t t = 0; t < 14; ++t) {
              bool truth = false;
              for (int j = 0; j < rm.robotCount(); ++j)
                if (j != i)
                  truth = truth || rm.conflict(i, {u, v}, j,
                                               {lattice::vertexAt(paths[static_cast<std::size_t>(j)], t),
                                                lattice::vertexAt(paths[static_cast<std::size_t>(j)], t + 1)});
              const bool seen = occ.blocked(i, u, v, t);
              CHECK(seen == truth);
              blocked += truth;
              ++checks;
            }
        }
    }
    // The walks meet often enough for the check to mean something.
    CHECK(blocked > checks / 20);
  }
}

TEST_CASE("Spread-out ways lead each robot to its goal and avoid a meeting that the shortest ways make") {
  // Two robots cross the middle of an open 5 x 5 grid: their only
  // shortest ways meet on the centre at step 2.
  const std::vector<std::string> rows(5, ".....");
  const Scenario sc =
      gridScenario(rows, {{{0.5, 2.5}, {4.5, 2.5}}, {{2.5, 0.5}, {2.5, 4.5}}}, RobotSpec::mobileDisc("", 0.3));
  const CollisionWorld world(sc);
  const RobotModels models(sc);
  const CrowdRoadmap rm(world, models.raw, {0, 1}, {sc.robots[0].start, sc.robots[1].start},
                        {sc.robots[0].goal, sc.robots[1].goal});
  for (int margin : {0, 4}) {
    const crowd::Spread spread(rm, margin, Deadline(), 1);
    CHECK(spread.meetings() == (margin == 0 ? 1 : 0));
    for (int i = 0; i < 2; ++i) {
      int v = rm.start(i), steps = 0;
      while (v != rm.goal(i) && steps <= 20) {
        const int next = spread.next(i, v);
        REQUIRE(next >= 0);
        const auto& nb = rm.neighbours(v);
        CHECK(std::find(nb.begin(), nb.end(), next) != nb.end());
        v = next;
        ++steps;
      }
      CHECK(v == rm.goal(i));
      CHECK(steps <= rm.distanceToGoal(i, rm.start(i)) + margin);
    }
  }
}

}  // namespace earc
