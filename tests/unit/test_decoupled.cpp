// ARC's subproblems and its decoupled solver: windows, expansion, horizons,
// budgets and priority orders.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/generators.hpp"
#include "earc/planning/arc.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/planning/planner.hpp"
#include "earc/util/kdtree.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"

using earc::test::fiveLinkArm;
using earc::test::line;

using namespace earc;

#include "arc_fixtures.hpp"

using namespace earc::arc_test;

TEST_CASE("A subproblem's window spans the conflict and its local query lies on the paths") {
  CrossingFixture f;
  PlannerSettings settings;
  settings.arc.initial_window = 8;
  Subproblem sub = f.subproblem(settings);
  CHECK(sub.t_start + 8 == static_cast<std::size_t>(f.c.t));
  CHECK(sub.t_end >= static_cast<std::size_t>(f.c.t) + 8);
  // The end moved past the crossing so that the local goals are apart.
  CHECK_FALSE(robotsTouch(*f.m.raw[0], sub.goals[0].data(), *f.m.raw[1], sub.goals[1].data()));
  for (int r = 0; r < 2; ++r) {
    CHECK(sub.starts[r] == std::vector<double>(f.paths[r].at(sub.t_start), f.paths[r].at(sub.t_start) + 3));
    CHECK(sub.region[r].contains(sub.starts[r].data()));
    CHECK(sub.region[r].contains(sub.goals[r].data()));
  }
  CHECK_FALSE(sub.whole_problem);
}

TEST_CASE("The decoupled solver builds its robots' roadmaps before its time budget starts") {
  // The discs' straight paths need no roadmap; the solver needs them, and
  // building them is not the search's time: with a budget of zero the
  // search gives up at once, yet the roadmap is there.
  CrossingFixture f;
  PlannerSettings settings;
  Subproblem sub = f.subproblem(settings);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  REQUIRE(roadmaps.built() == 0);
  SolverContext ctx{f.world, f.m.raw, roadmaps, f.paths, sub, Deadline(10), 7};
  DecoupledSettings none;
  none.time_budget_s = 0;
  CHECK_FALSE(DecoupledSolver(none).solve(ctx).solution.has_value());
  CHECK(roadmaps.built() == 1);  // equal discs share one
  // With time, the same subproblem is solved on that roadmap.
  CHECK(DecoupledSolver().solve(ctx).solution.has_value());
  CHECK(roadmaps.built() == 1);
}

TEST_CASE("Expanding a subproblem doubles its window and grows its region until it is the whole problem") {
  CrossingFixture f;
  PlannerSettings settings;
  settings.arc.initial_window = 4;
  settings.arc.max_expansions = 5;
  Subproblem a = f.subproblem(settings);
  Subproblem b = f.subproblem(settings, 1);
  CHECK(a.t_start - b.t_start == 4);
  CHECK(b.region[0].hi[0] - b.region[0].lo[0] > a.region[0].hi[0] - a.region[0].lo[0]);
  Subproblem last = f.subproblem(settings, 5);
  CHECK(last.whole_problem);
  CHECK(last.t_start == 0);
  CHECK(last.t_end == 80);
  CHECK(last.goals[0] == f.s.robots[0].goal);
}

TEST_CASE("A subproblem whose window and regions already cover everything is the whole problem before the last level") {
  // Retrying it level by level would solve the same subproblem again with
  // the same budgets; marked whole, ARC goes on to larger budgets.
  CrossingFixture f;
  PlannerSettings settings;
  settings.arc.initial_window = 4;
  settings.arc.max_expansions = 12;
  int first_saturated = -1;
  for (int level = 0; level <= settings.arc.max_expansions; ++level) {
    CAPTURE(level);
    Subproblem sub = f.subproblem(settings, level);
    bool covers = sub.t_start == 0 && sub.t_end == 80;
    for (int r = 0; r < 2; ++r) {
      ConfigBox full;
      f.m.raw[static_cast<std::size_t>(r)]->samplingBounds(f.world.workspace(), full.lo, full.hi);
      covers = covers && sub.region[static_cast<std::size_t>(r)].lo == full.lo &&
               sub.region[static_cast<std::size_t>(r)].hi == full.hi;
    }
    CHECK(sub.whole_problem == (covers || level == settings.arc.max_expansions));
    if (covers && first_saturated < 0) first_saturated = level;
  }
  CHECK(first_saturated > 0);
  CHECK(first_saturated < settings.arc.max_expansions);
}

TEST_CASE("A subproblem spanning the paths whose regions together span the workspace is the whole problem") {
  // Robot a's own region is not yet the full box, but the regions together
  // cover the workspace: the levels left would only widen a's region a
  // margin a level, each at the same budget.
  CrossingFixture f;
  PlannerSettings settings;
  settings.arc.initial_window = 64;  // the window spans both paths from level 0
  settings.arc.max_expansions = 12;
  ConfigBox full;
  f.m.raw[0]->samplingBounds(f.world.workspace(), full.lo, full.hi);
  Subproblem one = f.subproblem(settings, 1);
  REQUIRE(one.t_start == 0);
  REQUIRE(one.t_end == 80);
  CHECK_FALSE(one.whole_problem);
  Subproblem two = f.subproblem(settings, 2);
  CHECK(two.whole_problem);
  CHECK_FALSE(two.region[0] == full);
}

TEST_CASE("The decoupled solver's expansion cap grows with the hierarchy's budget scale") {
  // Past ARC's last level the same subproblem is retried with a larger
  // budget scale: a search cut off by its expansion cap must get further.
  CrossingFixture f;
  PlannerSettings settings;
  Subproblem sub = f.subproblem(settings);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  DecoupledSettings tight;
  tight.max_expansions = 3;
  tight.expansions_per_horizon_step = 0;
  tight.avoid_others = false;
  SolverContext ctx{f.world, f.m.raw, roadmaps, f.paths, sub, Deadline(10), 7};
  CHECK_FALSE(DecoupledSolver(tight).solve(ctx).solution.has_value());
  ctx.budget_scale = 2000;
  CHECK(DecoupledSolver(tight).solve(ctx).solution.has_value());
}

TEST_CASE("A robot with no way past the robots outside its group ends the decoupled attempt at once") {
  // Discs a and b cross; disc c rests for good where a's window ends. a,
  // planned first, finds no way to hold its goal; behind b it would find
  // none either, so the solver says so and tries no other order.
  CrossingFixture f(0.2);
  PlannerSettings settings;
  const Subproblem sub = f.subproblem(settings);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  SolverContext ctx{f.world, f.m.raw, roadmaps, f.paths, sub, Deadline(10), 7};
  REQUIRE(DecoupledSolver().solve(ctx).solution.has_value());  // with c out of the way
  f.paths[2] = Path(3);
  for (int t = 0; t <= 80; ++t) f.paths[2].push(sub.goals[0].data());
  const SolverOutcome out = DecoupledSolver().solve(ctx);
  CHECK_FALSE(out.solution.has_value());
  CHECK(out.detail == "robot 0 has no way past the robots outside the group, in any order");

  // The search says whether it ran out of ways or stopped short of them.
  QueryGraph graph(roadmaps.forRobot(0), *f.m.raw[0], &sub.region[0]);
  const int sv = graph.addVertex(sub.starts[0].data(), 10), gv = graph.addVertex(sub.goals[0].data(), 10);
  const std::vector<MovingObstacle> resting{{f.m.raw[2], &f.paths[2], sub.t_start, 2}};
  const std::size_t window = sub.t_end - sub.t_start;
  SearchEnd end = SearchEnd::Found;
  CHECK_FALSE(spaceTimeSearch(graph, sv, gv, resting, 200, window, Deadline(), 100000, false, &end));
  CHECK(end == SearchEnd::NoWay);
  CHECK_FALSE(spaceTimeSearch(graph, sv, gv, {}, 200, window, Deadline(), 0, false, &end));
  CHECK(end == SearchEnd::Capped);
  CHECK_FALSE(spaceTimeSearch(graph, sv, gv, {}, 200, window, Deadline(-1.0), 100000, false, &end));
  CHECK(end == SearchEnd::OutOfTime);
  CHECK(spaceTimeSearch(graph, sv, gv, {}, 200, window, Deadline(), 100000, false, &end));
  CHECK(end == SearchEnd::Found);
}

TEST_CASE("The decoupled solver's robots arrive within the window and 50 steps, more on the hierarchy's retries") {
  // Discs a and b cross; disc c rests on a's way, in a region too narrow
  // to pass it, until 80 steps after the window: a can get by only after
  // that, later than its horizon allows.
  CrossingFixture f(0.1);
  PlannerSettings settings;
  settings.arc.region_margin = 0.2;
  settings.arc.initial_window = 16;
  const Subproblem sub = f.subproblem(settings);
  const std::size_t window = sub.t_end - sub.t_start;
  f.paths[2] = Path(3);
  const double in_the_way[3] = {4.5, 5, 0}, away[3] = {9, 9, 0};
  for (std::size_t t = 0; t <= sub.t_end + 80; ++t) f.paths[2].push(in_the_way);
  f.paths[2].push(away);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  SolverContext ctx{f.world, f.m.raw, roadmaps, f.paths, sub, Deadline(10), 7};
  CHECK_FALSE(DecoupledSolver().solve(ctx).solution.has_value());
  DecoupledSettings patient;
  patient.horizon_steps = 200;
  const SolverOutcome waited = DecoupledSolver(patient).solve(ctx);
  REQUIRE(waited.solution.has_value());
  CHECK(waited.solution->length() > window + 80);
  // Past ARC's last level the budget scale grows the horizon too.
  ctx.budget_scale = 4;
  CHECK(DecoupledSolver().solve(ctx).solution.has_value());
}

TEST_CASE("A failed decoupled attempt says how its last priority order failed") {
  // Two discs swap places along a line, in a region too narrow to pass:
  // either one, planned first, goes straight through; the other then has
  // no way past it, in both orders.
  Scenario s = openScenario(10);
  s.robots = {disc("a", 0.2, {3, 5, 0}, {7, 5, 0}), disc("b", 0.2, {7, 5, 0}, {3, 5, 0})};
  RobotModels m(s);
  CollisionWorld world(s);
  std::vector<Path> paths{line({3, 5, 0}, {7, 5, 0}, 81), line({7, 5, 0}, {3, 5, 0}, 81)};
  auto conflict = ConflictDetector(m.raw).first(pathPointers(paths));
  REQUIRE(conflict.has_value());
  PlannerSettings settings;
  settings.arc.region_margin = 0.2;
  const Subproblem sub = createSubproblem(*conflict, {0, 1}, 0, m.raw, paths, world, settings);
  RoadmapSet roadmaps(world, m.raw, 300, 10, 1);
  SolverContext ctx{world, m.raw, roadmaps, paths, sub, Deadline(10), 7};
  const SolverOutcome out = DecoupledSolver().solve(ctx);
  CHECK_FALSE(out.solution.has_value());
  CHECK(out.detail == "2 priority orders failed; in the last, robot 0 (2 of 2): no way");
}

TEST_CASE("After a failed priority order the robot that failed goes first, and no order is tried twice") {
  std::mt19937_64 rng(5);
  using Order = std::vector<std::size_t>;
  // Robot 2 found no way behind 0 and 1: it picks its way first next.
  CHECK(nextPriorityOrder({{0, 1, 2}}, 2, rng) == Order{2, 0, 1});
  CHECK(nextPriorityOrder({{3, 1, 0, 2}}, 0, rng) == Order{0, 3, 1, 2});
  // The robot planned first failed (out of expansions): moving it to the
  // front gives the same order, so an untried one comes instead.
  std::vector<Order> tried{{0, 1, 2}};
  for (int k = 0; k < 5; ++k) {
    const Order next = nextPriorityOrder(tried, tried.back().front(), rng);
    REQUIRE(next.size() == 3);
    CHECK(std::find(tried.begin(), tried.end(), next) == tried.end());
    CHECK(std::is_permutation(next.begin(), next.end(), tried.front().begin()));
    tried.push_back(next);
  }
  // All 6 orders of 3 robots tried: none is left.
  CHECK(nextPriorityOrder(tried, 1, rng).empty());
  // Beyond 5 robots an untried order is drawn by shuffling.
  std::vector<Order> many{{0, 1, 2, 3, 4, 5, 6}};
  const Order next = nextPriorityOrder(many, 0, rng);
  CHECK(next != many.front());
  CHECK(std::is_permutation(next.begin(), next.end(), many.front().begin()));
  // Every order of 6 robots tried (a whole-problem prioritized plan may
  // try up to 1,000): none is left, and the search for one ends.
  std::vector<Order> all;
  Order six{0, 1, 2, 3, 4, 5};
  do all.push_back(six);
  while (std::next_permutation(six.begin(), six.end()));
  CHECK(nextPriorityOrder(all, 3, rng).empty());
  all.pop_back();
  CHECK(nextPriorityOrder(all, 3, rng) == Order{5, 4, 3, 2, 1, 0});
}

TEST_CASE("The decoupled solver tries each priority order of a group once at most") {
  // Three discs cross; no search may expand a state, so every order fails
  // at the robot planned first. Ten orders allowed, six exist.
  Scenario s = openScenario(10);
  s.robots = {disc("a", 0.2, {3, 5, 0}, {7, 5, 0}), disc("b", 0.2, {5, 3, 0}, {5, 7, 0}),
              disc("c", 0.2, {3.2, 4.6, 0}, {7.2, 5.4, 0})};
  RobotModels m(s);
  CollisionWorld world(s);
  std::vector<Path> paths{line({3, 5, 0}, {7, 5, 0}, 81), line({5, 3, 0}, {5, 7, 0}, 81),
                          line({3.2, 4.6, 0}, {7.2, 5.4, 0}, 81)};
  auto conflict = ConflictDetector(m.raw).first(pathPointers(paths));
  REQUIRE(conflict.has_value());
  PlannerSettings settings;
  const Subproblem sub = createSubproblem(*conflict, {0, 1, 2}, 0, m.raw, paths, world, settings);
  RoadmapSet roadmaps(world, m.raw, 300, 10, 1);
  SolverContext ctx{world, m.raw, roadmaps, paths, sub, Deadline(10), 7};
  DecoupledSettings capped;
  capped.max_expansions = 0;
  capped.max_orders = 10;
  const SolverOutcome out = DecoupledSolver(capped).solve(ctx);
  CHECK_FALSE(out.solution.has_value());
  CHECK(out.detail.rfind("6 priority orders failed; in the last, robot ", 0) == 0);
  CHECK(out.detail.find("(1 of 3): expansion cap") != std::string::npos);
}

TEST_CASE("Told to ignore the robots outside, the decoupled solver plans through one that walls its group in") {
  // ARC's retries of a whole problem do so every other time: the robot in
  // the way then meets the answer as a conflict of its own.
  CrossingFixture f;
  std::vector<Path> paths = f.paths;
  Path parked(3);  // robot b at rest across a's way for good
  for (int t = 0; t <= 80; ++t) {
    const double q[3] = {5, 5, 0};
    parked.push(q);
  }
  paths[1] = parked;
  PlannerSettings settings;
  settings.arc.initial_window = 16;
  settings.arc.region_margin = 0.2;  // too narrow a region to pass b
  Subproblem sub = createSubproblem(f.c, {0}, 0, f.m.raw, paths, f.world, settings);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  SolverContext ctx{f.world, f.m.raw, roadmaps, paths, sub, Deadline(10), 7};
  const SolverOutcome avoiding = DecoupledSolver().solve(ctx);
  CHECK_FALSE(avoiding.solution.has_value());
  ctx.ignore_others = true;
  const SolverOutcome ignoring = DecoupledSolver().solve(ctx);
  REQUIRE(ignoring.solution.has_value());
  const std::vector<MovingObstacle> b{{f.m.raw[1], &paths[1], sub.t_start, 1}};
  CHECK_FALSE(clearOfMoving(*f.m.raw[0], ignoring.solution->paths[0], b));
}

TEST_CASE("A robot standing at its goal keeps it while the robot that meets it goes around") {
  // b arrived at (5, 5) before the window; a's straight line runs through
  // it. Planned in the listed order, a would go straight through b's spot
  // and push b off its goal and back.
  Scenario sc = openScenario(10);
  sc.robots = {disc("a", 0.2, {2, 5, 0}, {8, 5, 0}), disc("b", 0.2, {5, 5, 0}, {5, 5, 0})};
  RobotModels m(sc);
  CollisionWorld world(sc);
  Path parked(3);
  parked.push(sc.robots[1].start.data());
  std::vector<Path> paths{line({2, 5, 0}, {8, 5, 0}, 121), parked};
  ConflictDetector detector(m.raw);
  const auto c = detector.first(pathPointers(paths));
  REQUIRE(c.has_value());
  PlannerSettings settings;
  const Subproblem sub = createSubproblem(*c, {0, 1}, 1, m.raw, paths, world, settings);
  RoadmapSet roadmaps(world, m.raw, 300, 10, 1);
  SolverContext ctx{world, m.raw, roadmaps, paths, sub, Deadline(10), 7};
  const SolverOutcome out = DecoupledSolver().solve(ctx);
  REQUIRE(out.solution.has_value());
  const Path& b = out.solution->paths[1];
  for (std::size_t t = 0; t < b.size(); ++t) CHECK(std::equal(b.at(t), b.at(t) + 3, sc.robots[1].start.data()));
  const Path& a = out.solution->paths[0];
  CHECK(std::equal(a.back(), a.back() + 3, sub.goals[0].data()));
}

namespace {

// Disc m drives along y = 5 through (5, 5), where disc p stands parked at
// its goal for good: their conflict's subproblem, with regions `margin`
// around the robots' window paths.
struct ParkedInTheWay {
  Scenario s;
  RobotModels m;
  CollisionWorld world;
  std::vector<Path> paths{line({3, 5, 0}, {7, 5, 0}, 81), line({{5, 5, 0}})};
  Subproblem sub;
  explicit ParkedInTheWay(double margin)
      : s(scenario()), m(s), world(s) {
    auto conflict = ConflictDetector(m.raw).first(pathPointers(paths));
    REQUIRE(conflict.has_value());
    PlannerSettings settings;
    settings.arc.region_margin = margin;
    sub = createSubproblem(*conflict, {0, 1}, 0, m.raw, paths, world, settings);
  }
  static Scenario scenario() {
    Scenario s = openScenario(10);
    s.robots = {arc_test::disc("m", 0.2, {3, 5, 0}, {7, 5, 0}), arc_test::disc("p", 0.2, {5, 5, 0}, {5, 5, 0})};
    return s;
  }
  // The answer went around the parked robot, which stayed still, and its
  // splice leaves no conflict.
  void checkAroundParked(const SolverOutcome& out) const {
    REQUIRE(out.solution.has_value());
    CHECK(out.detail == "around the parked robots");
    const LocalSolution& sol = *out.solution;
    for (std::size_t t = 0; t < sol.length(); ++t)
      CHECK(std::equal(sol.paths[1].at(t), sol.paths[1].at(t) + 3, sub.starts[1].data()));
    std::vector<Path> plan = paths;
    splice(plan, sub, sol);
    CHECK_FALSE(ConflictDetector(m.raw).first(pathPointers(plan)).has_value());
  }
};

}  // namespace

TEST_CASE("The decoupled solver takes a robot around a parked one over the whole workspace before moving it") {
  // In regions too narrow to pass, m cannot get by p, and p cannot step
  // aside far enough: no order answers. Over the whole workspace m goes
  // around p, which stays where it is.
  ParkedInTheWay f(0.2);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  SolverContext ctx{f.world, f.m.raw, roadmaps, f.paths, f.sub, Deadline(10), 7};
  CHECK_FALSE(DecoupledSolver().solve(ctx).solution.has_value());  // the default
  DecoupledSettings around;
  around.parked_detour = true;
  f.checkAroundParked(DecoupledSolver(around).solve(ctx));
}

TEST_CASE("The coupled solver first plans the robots that are not parked, the parked ones held still") {
  ParkedInTheWay f(1.0);
  RoadmapSet roadmaps(f.world, f.m.raw, 300, 10, 1);
  SolverContext ctx{f.world, f.m.raw, roadmaps, f.paths, f.sub, Deadline(10), 7};
  CoupledSolverSettings held;
  held.parked_held = true;
  f.checkAroundParked(CoupledSubproblemSolver(held).solve(ctx));
}
