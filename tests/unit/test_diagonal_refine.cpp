// The lattice refinement's diagonal steps on a grid map: diagonals only
// across free squares, its tick conflict table against the validator and a
// fine sampling of the motions, and refinement with them never returning an
// invalid or costlier plan.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/crowd.hpp"
#include "earc/planning/crowd_roadmap.hpp"
#include "earc/planning/lacam.hpp"
#include "earc/planning/lattice_lns.hpp"
#include "earc/planning/planner.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/scene/scenario.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"
#include "../../src/planning/tick_search.hpp"

namespace earc {
namespace {

struct TickWorld {
  Scenario sc;
  CollisionWorld world;
  RobotModels models;
  CrowdRoadmap rm;
  TickWorld(const std::vector<std::string>& rows, const std::vector<std::pair<geo::Vec2, geo::Vec2>>& moves)
      : sc(test::gridScenario(rows, moves, RobotSpec::mobileDisc("", 0.3))), world(sc), models(sc),
        rm(world, models.raw, test::allRobots(sc), test::robotEnds(sc, true), test::robotEnds(sc, false)) {}
};

int vertexOf(const CrowdRoadmap& rm, double x, double y) {
  for (int v = 0; v < rm.vertexCount(); ++v)
    if (geo::norm(rm.position(v) - geo::Vec2{x, y}) < 1e-9) return v;
  return -1;
}

// Where a robot making a move of type a from u (begun at tick 0) is at time
// step s, staying at its end after; per_tick time steps per tick.
geo::Vec2 placeAt(const ticks::Lattice& lat, int u, int a, double s) {
  const CrowdRoadmap& rm = lat.roadmap();
  int w = u;
  for (const auto& [x, b] : lat.moves(u))
    if (b == a) w = x;
  const double f = std::clamp(s / (lat.stepsPerTick() * ticks::ticksOf(a)), 0.0, 1.0);
  return rm.position(u) + (rm.position(w) - rm.position(u)) * f;
}

// The validator's verdict, at its instants (steps and midpoints), on two
// robots making moves a from u and b from w, begun together, while the
// first one lasts.
bool validatorSeesTouch(const TickWorld& tw, const ticks::Lattice& lat, int u, int a, int w, int b) {
  InstantChecker checker(tw.sc);
  const int both[2] = {0, 1};
  const int steps = lat.stepsPerTick() * ticks::ticksOf(a);
  for (int k = 0; k <= 2 * steps; ++k) {
    const geo::Vec2 p = placeAt(lat, u, a, 0.5 * k), r = placeAt(lat, w, b, 0.5 * k);
    const double qa[3] = {p.x, p.y, 0.0}, qb[3] = {r.x, r.y, 0.0};
    const double* q[2] = {qa, qb};
    std::vector<Violation> out;
    checker.checkGeometry(both, q, k * 0.5, out);
    for (const auto& v : out)
      if (v.type == Violation::Type::RobotRobot) return true;
  }
  return false;
}

// The smallest distance of the two motions while the first one lasts,
// sampled 400 times a tick.
double sampledApproach(const ticks::Lattice& lat, int u, int a, int w, int b) {
  const int n = 400 * ticks::ticksOf(a);
  const double steps = lat.stepsPerTick() * ticks::ticksOf(a);
  double best = 1e300;
  for (int k = 0; k <= n; ++k) {
    const double s = steps * k / n;
    best = std::min(best, geo::norm(placeAt(lat, u, a, s) - placeAt(lat, w, b, s)));
  }
  return best;
}

// A tick path of one move of type a from u, then standing at its end;
// empty when there is no such move.
ticks::TickPath oneMove(const ticks::Lattice& lat, int u, int a) {
  ticks::TickPath p = {u};
  if (a == 0) return p;
  for (int k = 1; k < ticks::ticksOf(a); ++k) p.push_back(-1);
  for (const auto& [x, b] : lat.moves(u))
    if (b == a) p.push_back(x);
  return p.back() < 0 ? ticks::TickPath{} : p;
}

// The vertex robot path p's tick t begins on and the tick's state.
std::pair<int, int> tickStateAt(const ticks::Lattice& lat, const ticks::TickPath& p, std::size_t t) {
  if (t + 1 >= p.size()) return {p.back(), 0};
  std::size_t t0 = t, t1 = t + 1;
  while (p[t0] < 0) --t0;
  while (p[t1] < 0) ++t1;
  return {p[t0], ticks::Lattice::state(lat.moveType(p[t0], p[t1]), static_cast<int>(t - t0))};
}

// Whether a move of type a from u begun at tick t meets any of `paths`,
// tick by tick and pair by pair (Lattice::meet, no occupancy).
bool meetsAnyone(const ticks::Lattice& lat, const std::vector<ticks::TickPath>& paths, int u, int a, std::size_t t) {
  for (int k = 0; k < ticks::ticksOf(a); ++k)
    for (const ticks::TickPath& p : paths) {
      const auto [w, s] = tickStateAt(lat, p, t + static_cast<std::size_t>(k));
      if (lat.meet(u, ticks::Lattice::state(a, k), w, s)) return true;
    }
  return false;
}

std::vector<Path> firstPaths(const TickWorld& tw, const std::vector<std::vector<int>>& configs) {
  return *crowdPaths(tw.rm, configs, tw.rm.stepsPerEdge(), test::robotEnds(tw.sc, true), test::robotEnds(tw.sc, false));
}

Solution solutionOf(const Scenario& sc, std::vector<Path> paths) {
  Solution s;
  s.scenario = sc.name;
  s.solved = true;
  s.paths = std::move(paths);
  return s;
}

}  // namespace

TEST_CASE("A diagonal step is taken only across four free cells; the validator refuses the disc cutting a corner") {
  // Row 0 on top: the blocked cell is (2, 1) in x, y.
  const TickWorld tw({".....", ".....", ".....", "..#..", "....."}, {{{0.5, 0.5}, {4.5, 4.5}}});
  const auto lat = ticks::Lattice::make(tw.rm);
  REQUIRE(lat.has_value());
  auto hasMove = [&](int u, int w) { return lat->moveType(u, w) > 0; };
  // (1.5, 1.5) -> (2.5, 2.5) passes the blocked cell's corner (2, 2), and
  // (2.5, 0.5) -> (1.5, 1.5) its corner (2, 1).
  const int c = vertexOf(tw.rm, 1.5, 1.5), d = vertexOf(tw.rm, 2.5, 2.5), f = vertexOf(tw.rm, 3.5, 3.5);
  REQUIRE(vertexOf(tw.rm, 2.5, 1.5) < 0);
  CHECK_FALSE(hasMove(c, d));
  CHECK_FALSE(hasMove(d, c));
  CHECK_FALSE(hasMove(vertexOf(tw.rm, 2.5, 0.5), c));
  CHECK(hasMove(d, f));
  CHECK(hasMove(vertexOf(tw.rm, 0.5, 0.5), c));
  // Every diagonal of the map: the validator accepts the disc along it,
  // and refuses it along each one refused that has both ends free.
  InstantChecker checker(tw.sc);
  const int one[1] = {0};
  auto obstacleHit = [&](int u, int w) {
    for (int k = 0; k <= 60; ++k) {
      const geo::Vec2 p = tw.rm.position(u) + (tw.rm.position(w) - tw.rm.position(u)) * (k / 60.0);
      const double q[3] = {p.x, p.y, 0.0};
      const double* qs[1] = {q};
      std::vector<Violation> out;
      checker.checkGeometry(one, qs, k, out);
      if (!out.empty()) return true;
    }
    return false;
  };
  int taken = 0, refused = 0;
  for (int u = 0; u < tw.rm.vertexCount(); ++u)
    for (const auto& [dc, dr] : {std::pair{1, 1}, std::pair{-1, 1}, std::pair{1, -1}, std::pair{-1, -1}}) {
      const int w = tw.rm.latticeOffset(u, dc, dr);
      if (w < 0) continue;
      const bool ok = hasMove(u, w);
      CHECK(ok != obstacleHit(u, w));
      taken += ok;
      refused += !ok;
    }
  CHECK(taken > 40);
  CHECK(refused == 8);  // the four diagonals past the blocked cell's corners, both ways
}

TEST_CASE("The tick conflict table agrees with a fine sampling and with the validator on every pair of moves") {
  const TickWorld tw(std::vector<std::string>(7, "......."), {{{0.5, 0.5}, {6.5, 6.5}}, {{6.5, 0.5}, {0.5, 6.5}}});
  const auto lat = ticks::Lattice::make(tw.rm);
  REQUIRE(lat.has_value());
  const double touch = 2.0 * tw.rm.radius();
  const int u = vertexOf(tw.rm, 3.5, 3.5);
  int pairs = 0, conflicts = 0, validator_touches = 0;
  for (int w = 0; w < tw.rm.vertexCount(); ++w) {
    if (w == u) continue;
    for (int a = 0; a < ticks::kMoveTypes; ++a)
      for (int b = 0; b < ticks::kMoveTypes; ++b) {
        std::vector<ticks::TickPath> paths = {oneMove(*lat, u, a), oneMove(*lat, w, b)};
        if (paths[0].empty() || paths[1].empty()) continue;  // no such move here
        ticks::Occupancy occ(*lat, paths);
        occ.remove(0);
        const bool table = occ.blocked(0, u, a, 0);
        const double d = sampledApproach(*lat, u, a, w, b);
        CAPTURE(u);
        CAPTURE(w);
        CAPTURE(a);
        CAPTURE(b);
        // The table is exact: it matches the sampling but where the
        // sampling's step can miss the closest instant.
        if (std::abs(d - touch) > 1e-3) CHECK(table == (d < touch));
        const bool validator = validatorSeesTouch(tw, *lat, u, a, w, b);
        CHECK((!validator || table));  // never less strict than the validator
        ++pairs;
        conflicts += table;
        validator_touches += validator;
      }
  }
  CHECK(pairs > 1000);
  CHECK(conflicts > 100);
  CHECK(validator_touches > 100);
  // The named cases: two diagonals crossing in an X conflict; a diagonal
  // beside a parallel axis move one cell over does not... and one that
  // cuts across the axis move's cell does.
  auto pairBlocked = [&](int p, int a, int q, int b) {
    std::vector<ticks::TickPath> paths = {oneMove(*lat, p, a), oneMove(*lat, q, b)};
    ticks::Occupancy occ(*lat, paths);
    occ.remove(0);
    return occ.blocked(0, p, a, 0);
  };
  const int x0 = vertexOf(tw.rm, 3.5, 3.5), x1 = vertexOf(tw.rm, 4.5, 3.5);
  CHECK(pairBlocked(x0, 5, x1, 6));  // (3,3)->(4,4) and (4,3)->(3,4): an X
  CHECK(validatorSeesTouch(tw, *lat, x0, 5, x1, 6));
  // A diagonal (3,3)->(4,4) beside an axis move (5,3)->(5,4): 1.5 cells apart at least.
  CHECK_FALSE(pairBlocked(x0, 5, vertexOf(tw.rm, 5.5, 3.5), 3));
  // ... and beside (4,3)->(4,4), which its disc sweeps past within 0.6.
  CHECK(pairBlocked(x0, 5, x1, 3));
  CHECK(validatorSeesTouch(tw, *lat, x0, 5, x1, 3));
}

TEST_CASE("The tick occupancy of a crowd answers as the pairwise conflict table, also after removals") {
  const TickWorld tw({"........", "..#.....", "........", ".....#..", "........", "........", ".#......", "........"},
                     {{{0.5, 0.5}, {7.5, 7.5}}});
  const auto lat = ticks::Lattice::make(tw.rm);
  REQUIRE(lat.has_value());
  std::mt19937 rng(7);
  auto pick = [&](std::size_t n) { return static_cast<std::size_t>(rng() % n); };
  // Random walks of waits and moves, each kept when it meets none of the
  // walks kept before (so that every slot holds one robot at most).
  constexpr std::size_t kTicks = 40;
  std::vector<ticks::TickPath> paths;
  for (int tries = 0; tries < 400 && paths.size() < 14; ++tries) {
    ticks::TickPath p = {static_cast<int>(pick(static_cast<std::size_t>(tw.rm.vertexCount())))};
    while (p.size() < 16) {
      const auto& moves = lat->moves(p.back());
      if (moves.empty() || pick(4) == 0) {
        p.push_back(p.back());
        continue;
      }
      const auto [w, a] = moves[pick(moves.size())];
      for (int k = 1; k < ticks::ticksOf(a); ++k) p.push_back(-1);
      p.push_back(w);
    }
    bool clear = true;
    for (std::size_t t = 0; t < kTicks && clear; ++t) {
      const auto [u, s] = tickStateAt(*lat, p, t);
      for (const auto& q : paths) {
        const auto [w, r] = tickStateAt(*lat, q, t);
        if (lat->meet(u, s, w, r)) clear = false;
      }
    }
    if (clear) paths.push_back(std::move(p));
  }
  REQUIRE(paths.size() >= 10);
  ticks::Occupancy occ(*lat, paths);
  std::vector<ticks::TickPath> in = paths;
  int asked = 0, blocked = 0;
  auto compare = [&]() {
    for (int q = 0; q < 600; ++q) {
      const int u = static_cast<int>(pick(static_cast<std::size_t>(tw.rm.vertexCount())));
      const auto& moves = lat->moves(u);
      const int a = pick(3) == 0 || moves.empty() ? 0 : moves[pick(moves.size())].second;
      const std::size_t t = pick(kTicks);
      CAPTURE(u);
      CAPTURE(a);
      CAPTURE(t);
      const bool b = occ.blocked(-2, u, a, t);
      CHECK(b == meetsAnyone(*lat, in, u, a, t));
      ++asked;
      blocked += b;
    }
  };
  compare();
  // Half of them out again: their slots must read empty.
  for (int i = 0; i < static_cast<int>(paths.size()); i += 2) occ.remove(i);
  in.clear();
  for (std::size_t i = 1; i < paths.size(); i += 2) in.push_back(paths[i]);
  compare();
  CHECK(blocked > asked / 10);
  CHECK(blocked < asked);
}

TEST_CASE("Refinement with diagonals never returns an invalid or costlier plan, and shortens a crowded one") {
  std::vector<std::string> rows(8, "........");
  rows[2] = "..##.#..";
  rows[5] = ".#..##..";
  const TickWorld tw(rows, test::shuffledMoves(rows, 24, 5));
  const LacamResult first = solveLacam(tw.rm, Deadline(10), 3);
  REQUIRE(first.solved);
  auto costOf = [](std::vector<Path> paths) {
    long long soc = 0;
    for (Path& p : paths) {
      p.dropTrailingWaits();
      soc += static_cast<long long>(p.size()) - 1;
    }
    return soc;
  };
  const std::vector<Path> grid = firstPaths(tw, first.configs);
  REQUIRE(validateSolution(tw.sc, solutionOf(tw.sc, grid)).valid);
  const long long before = costOf(grid);
  long long last = before;
  for (int rounds : {1, 10, 300}) {
    CAPTURE(rounds);
    LatticeRefineStats st;
    const auto paths = refineWithDiagonals(tw.rm, first.configs, Deadline(), 3, test::robotEnds(tw.sc, true),
                                           test::robotEnds(tw.sc, false), st, rounds);
    REQUIRE(paths.has_value());
    const ValidationReport rep = validateSolution(tw.sc, solutionOf(tw.sc, *paths));
    CHECK(rep.valid);
    for (const auto& v : rep.violations) MESSAGE(v.detail);
    const long long after = costOf(*paths);
    CHECK(after <= last);
    REQUIRE(st.steps_per_tick.has_value());
    CHECK(st.sum_of_costs_after * *st.steps_per_tick == after);
    REQUIRE(st.axis.has_value());
    CHECK(st.sum_of_costs_before == 2 * st.axis->sum_of_costs_after);  // a roadmap step is two ticks
    last = after;
  }
  CHECK(last < before);

  // Through the method, with --refine: valid, and never costlier than without diagonals.
  PlannerSettings s;
  s.method = Method::Lacam;
  s.time_limit_s = 60;
  s.seed = 3;
  s.work_budgets = true;
  s.post.refine_s = 0.3;
  const PlanResult r = plan(tw.sc, s);
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(tw.sc, r.solution).valid);
  REQUIRE(r.stats.lacam.has_value());
  CHECK(*r.stats.sum_of_costs <= *r.stats.lacam->first_sum_of_costs);
  // Some robot beats its 4-connected shortest way: a diagonal step.
  int shorter = 0;
  for (int i = 0; i < tw.rm.robotCount(); ++i) {
    Path p = r.solution.paths[static_cast<std::size_t>(i)];
    p.dropTrailingWaits();
    shorter += static_cast<long long>(p.size()) - 1 <
               static_cast<long long>(tw.rm.distanceToGoal(i, tw.rm.start(i))) * tw.rm.stepsPerEdge();
  }
  CHECK(shorter > 0);
}

TEST_CASE("Off a grid map's cells, or with discs too small for one robot per slot, there are no diagonal steps") {
  Scenario sc = test::gridScenario({"....", "...."}, {{{0.5, 0.5}, {3.5, 1.5}}}, RobotSpec::mobileDisc("", 0.2));
  const CollisionWorld world(sc);
  const RobotModels models(sc);
  const CrowdRoadmap small(world, models.raw, {0}, {sc.robots[0].start}, {sc.robots[0].goal});
  CHECK_FALSE(ticks::Lattice::make(small).has_value());
  // A start off the lattice (between cells).
  sc = test::gridScenario({"....", "...."}, {{{0.75, 0.5}, {3.5, 1.5}}}, RobotSpec::mobileDisc("", 0.3));
  const CollisionWorld world2(sc);
  const RobotModels models2(sc);
  const CrowdRoadmap off(world2, models2.raw, {0}, {sc.robots[0].start}, {sc.robots[0].goal});
  CHECK_FALSE(ticks::Lattice::make(off).has_value());
}

}  // namespace earc
