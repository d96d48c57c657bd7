// Plan compaction: robots retimed along their own routes, leaving out the
// waits nothing needs, keeping the ones that let others pass, and never
// arriving at a goal that someone crosses later; the most delayed robots'
// routes shortcut; ARC's coupled answers time-stamped robot by robot.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/generators.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/arc.hpp"
#include "earc/planning/compact.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/planning/coupled_solver.hpp"
#include "earc/planning/planner.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"

using namespace earc;

namespace {

RobotSpec compactDisc(const std::string& name, std::vector<double> start, std::vector<double> goal) {
  RobotSpec s = RobotSpec::mobileDisc(name, 0.3);
  s.start = std::move(start);
  s.goal = std::move(goal);
  return s;
}

// `waits` copies of the path's first state before it.
Path waitFirst(const Path& p, int waits) {
  Path out(p.dim());
  for (int k = 0; k < waits; ++k) out.push(p.at(0));
  out.append(p);
  return out;
}

Scenario compactScenario(std::vector<RobotSpec> robots) {
  Scenario s;
  s.name = "compact";
  s.workspace = {{0, 0}, {12, 12}};
  s.robots = std::move(robots);
  return s;
}

struct CompactCase {
  Scenario scenario;
  RobotModels models;
  explicit CompactCase(std::vector<RobotSpec> robots)
      : scenario(compactScenario(std::move(robots))), models(scenario) {}
  bool valid(const std::vector<Path>& paths) const {
    Solution sol;
    sol.solved = true;
    sol.paths = paths;
    sol.scenario = scenario.name;
    sol.nameRobots(scenario);
    const ValidationReport rep = validateSolution(scenario, sol);
    return rep.valid;
  }
};

}  // namespace

TEST_CASE("Compaction leaves out a wait that nothing needs, and keeps the route") {
  CompactCase c({compactDisc("a", {1, 1, 0}, {1, 9, 0}), compactDisc("b", {9, 1, 0}, {9, 9, 0})});
  // Steps of 0.05, the default resolution.
  std::vector<Path> paths{waitFirst(test::line({1, 1, 0}, {1, 9, 0}, 161), 10), test::line({9, 1, 0}, {9, 9, 0}, 161)};
  REQUIRE(c.valid(paths));
  const Path b_before = paths[1];
  const CompactReport rep = compactPlan(c.models.raw, paths, nullptr, Deadline());
  CHECK(rep.robots_retimed == 1);
  CHECK(rep.steps_saved == 10);
  CHECK(paths[0] == test::line({1, 1, 0}, {1, 9, 0}, 161));
  CHECK(paths[1] == b_before);
  CHECK(c.valid(paths));
}

TEST_CASE("Compaction keeps the waits that let a crossing robot pass, and the plan stays valid") {
  // b crosses a's line at (6, 6) at step 100; a waited at its start for
  // 60 steps, more than it needs (about 13).
  CompactCase c({compactDisc("a", {6, 1, 0}, {6, 11, 0}), compactDisc("b", {1, 6, 0}, {11, 6, 0})});
  const Path a_straight = test::line({6, 1, 0}, {6, 11, 0}, 201);
  std::vector<Path> paths{waitFirst(a_straight, 60), test::line({1, 6, 0}, {11, 6, 0}, 201)};
  REQUIRE(c.valid(paths));
  REQUIRE_FALSE(c.valid({a_straight, paths[1]}));  // without waiting they meet
  const std::size_t before = paths[0].size();
  const CompactReport rep = compactPlan(c.models.raw, paths, nullptr, Deadline());
  CHECK(rep.steps_saved > 0);
  CHECK(paths[0].size() < before);
  CHECK(paths[0].size() > a_straight.size());  // some waiting stays
  CHECK(routeOf(paths[0]) == routeOf(a_straight));
  CHECK(c.valid(paths));
  ConflictDetector detector(c.models.raw);
  CHECK_FALSE(detector.first(pathPointers(paths)).has_value());
}

TEST_CASE("Compaction does not bring a robot to a goal that another robot crosses later") {
  // a's goal (6, 6) lies on b's line, which b crosses at step 120 after
  // 20 waits; a could get there by step 100, but could not stay.
  CompactCase c({compactDisc("a", {6, 1, 0}, {6, 6, 0}), compactDisc("b", {1, 6, 0}, {11, 6, 0})});
  const Path a_straight = test::line({6, 1, 0}, {6, 6, 0}, 101);
  const Path b_straight = test::line({1, 6, 0}, {11, 6, 0}, 201);
  std::vector<Path> paths{waitFirst(a_straight, 160), waitFirst(b_straight, 20)};
  REQUIRE(c.valid(paths));
  compactPlan(c.models.raw, paths, nullptr, Deadline());
  CHECK(c.valid(paths));
  // b, which had nothing to wait for, goes straight; a arrives only once
  // b is clear of its goal (centres 0.6 apart: b past x = 6.6).
  CHECK(paths[1] == b_straight);
  std::size_t clear = 0;
  while (paths[1].at(clear)[0] <= 6.6) ++clear;
  CHECK(paths[0].size() - 1 >= clear);
  CHECK(paths[0].size() < a_straight.size() + 160);
}

TEST_CASE("Compaction after an expired deadline changes nothing and says it was interrupted") {
  CompactCase c({compactDisc("a", {1, 1, 0}, {1, 9, 0})});
  std::vector<Path> paths{waitFirst(test::line({1, 1, 0}, {1, 9, 0}, 161), 10)};
  const std::vector<Path> before = paths;
  const CompactReport rep = compactPlan(c.models.raw, paths, nullptr, Deadline(0.0));
  CHECK(rep.interrupted);
  CHECK(paths == before);
}

TEST_CASE("A robot held to a slow straight motion goes at full speed where the obstacles allow") {
  // a takes 0.025 a step, half what the resolution allows, as a robot
  // moved along with a slower one in a composite motion does.
  CompactCase c({compactDisc("a", {1, 1, 0}, {1, 9, 0}), compactDisc("b", {9, 1, 0}, {9, 9, 0})});
  std::vector<Path> paths{test::line({1, 1, 0}, {1, 9, 0}, 321), test::line({9, 1, 0}, {9, 9, 0}, 161)};
  REQUIRE(c.valid(paths));
  std::vector<Path> slow = paths;
  CHECK(compactPlan(c.models.raw, slow, nullptr, Deadline()).robots_retimed == 0);  // no waits to leave out
  const CollisionWorld world(c.scenario);
  const CompactReport rep = compactPlan(c.models.raw, paths, &world, Deadline());
  CHECK(rep.steps_saved == 160);
  CHECK(paths[0].size() == 161);
  CHECK(paths[0].back()[1] == 9.0);
  CHECK(c.valid(paths));
}

// From (1, 1) to (1, 9) by way of (5, 5), at full speed (steps of 0.05).
Path shortcutDetour() {
  Path p = test::line({1, 1, 0}, {5, 5, 0}, 115);
  const Path back = test::line({5, 5, 0}, {1, 9, 0}, 115);
  for (std::size_t t = 1; t < back.size(); ++t) p.push(back.at(t));
  return p;
}

TEST_CASE("Shortcuts cut the detour of the robot furthest behind, where compaction finds nothing") {
  CompactCase c({compactDisc("a", {1, 1, 0}, {1, 9, 0}), compactDisc("b", {9, 1, 0}, {9, 9, 0})});
  const CollisionWorld world(c.scenario);
  const std::vector<Path> before{shortcutDetour(), test::line({9, 1, 0}, {9, 9, 0}, 161)};
  REQUIRE(c.valid(before));
  std::vector<Path> paths = before;
  // No waits, no slow motion: nothing to retime.
  CHECK(compactRobots(c.models.raw, paths, {0, 1}, &world, Deadline(), 1, 8).steps_saved == 0);
  CHECK(paths == before);
  const CompactReport rep = shortcutRobots(c.models.raw, paths, {0, 1}, world, Deadline(), 1, 16, 7);
  CHECK(rep.robots_shortcut == 1);
  CHECK(rep.steps_saved == static_cast<std::int64_t>(before[0].size() - paths[0].size()));
  CHECK(paths[0].size() < before[0].size());
  CHECK(paths[1] == before[1]);  // only the robot furthest behind
  CHECK(std::vector<double>(paths[0].back(), paths[0].back() + 3) == std::vector<double>{1, 9, 0});
  CHECK(c.valid(paths));
  // The stretches follow the seed: the same seed cuts the same way, and
  // with two tries apiece some seeds cut differently.
  const auto cutWith = [&](std::uint64_t seed) {
    std::vector<Path> again = before;
    shortcutRobots(c.models.raw, again, {0, 1}, world, Deadline(), 1, 2, seed);
    return again[0];
  };
  CHECK(cutWith(7) == cutWith(7));
  bool differs = false;
  for (std::uint64_t seed = 1; seed <= 8 && !differs; ++seed) differs = !(cutWith(seed) == cutWith(seed + 100));
  CHECK(differs);
}

TEST_CASE("Shortcuts stay clear of the obstacles and of a robot parked on the way") {
  // A wall reaches from the left to x = 3 at y = 5, and b stands at
  // (3.6, 5): a may cross y = 5 only right of x = 4.2.
  CompactCase c({compactDisc("a", {1, 1, 0}, {1, 9, 0}), compactDisc("b", {3.6, 5, 0}, {3.6, 5, 0})});
  c.scenario.obstacles.push_back(Obstacle::makeBox({1.5, 5}, {3.0, 0.6}, 0.0));
  const CollisionWorld world(c.scenario);
  const std::vector<Path> before{shortcutDetour(), test::line({{3.6, 5, 0}})};
  REQUIRE(c.valid(before));
  std::vector<Path> paths = before;
  const CompactReport rep = shortcutRobots(c.models.raw, paths, {0, 1}, world, Deadline(), 2, 64, 7);
  CHECK(c.valid(paths));
  CHECK(rep.robots_shortcut == 1);  // cut where it could
  CHECK(paths[0].size() < before[0].size());
  CHECK(rep.steps_saved == static_cast<std::int64_t>(before[0].size() - paths[0].size()));
  for (std::size_t t = 0; t + 1 < paths[0].size(); ++t) {
    const double* p = paths[0].at(t);
    const double* q = paths[0].at(t + 1);
    if ((p[1] - 5) * (q[1] - 5) <= 0) CHECK(std::min(p[0], q[0]) >= 4.2);
  }
}

// How far a robot's path takes it (in the plane, or summed over joints).
double travelled(const Path& p, bool mobile) {
  double d = 0;
  for (std::size_t t = 1; t < p.size(); ++t) {
    if (mobile) {
      d += std::hypot(p.at(t)[0] - p.at(t - 1)[0], p.at(t)[1] - p.at(t - 1)[1]);
    } else {
      for (int j = 0; j < p.dim(); ++j) d += std::abs(p.at(t)[j] - p.at(t - 1)[j]);
    }
  }
  return d;
}

TEST_CASE("Compacted ARC plans keep every route, arrive no later and validate, on mobile robots and arms") {
  gen::MobileSettings ms;
  ms.robots = 16;
  ms.obstacles = 12;
  ms.seed = 3;
  gen::ArmSettings as;
  as.robots = 8;
  as.obstacles = gen::defaultArmObstacles(8);
  as.seed = 2;
  for (const Scenario& s : {gen::generateMobile(ms), gen::generateArms(as)}) {
    CAPTURE(s.name);
    PlannerSettings settings;
    settings.work_budgets = true;  // the same plan twice, under sanitizers too
    settings.time_limit_s = 60;
    const PlanResult plain = plan(s, settings);
    REQUIRE(plain.solution.solved);
    settings.post.compact = true;
    const PlanResult compacted = plan(s, settings);
    REQUIRE(compacted.solution.solved);  // plan() validates it
    const auto& st = compacted.stats;
    REQUIRE(st.compact);
    CHECK_FALSE(st.compact->rejected);
    CHECK(st.compact->sum_of_costs_before == plain.stats.sum_of_costs);
    CHECK(st.compact->makespan_before == plain.stats.makespan);
    CHECK(*st.sum_of_costs == *plain.stats.sum_of_costs - st.compact->steps_saved);
    CHECK(*st.makespan <= *plain.stats.makespan);
    const bool mobile = s.robots.front().kind == RobotKind::Mobile;
    for (std::size_t r = 0; r < s.robots.size(); ++r) {
      const Path& before = plain.solution.paths[r];
      const Path& after = compacted.solution.paths[r];
      CHECK(after.size() <= before.size());
      CHECK(travelled(after, mobile) == doctest::Approx(travelled(before, mobile)).epsilon(1e-9));
    }
    // Without the world, waits are all it leaves out: the same states in
    // the same order.
    std::vector<Path> paths = plain.solution.paths;
    compactPlan(RobotModels(s).raw, paths, nullptr, Deadline());
    for (std::size_t r = 0; r < s.robots.size(); ++r)
      CHECK(routeOf(paths[r]) == routeOf(plain.solution.paths[r]));
  }
}

TEST_CASE("A local solution's robots are retimed inside their window against the robots outside it") {
  // a and b, one group, answered over 321 steps: a at half speed, b at
  // full speed then waiting. c, outside the group, stands on a's route at
  // (1, 5) until step 100, then steps aside to (2, 5) by step 120.
  CompactCase c({compactDisc("a", {1, 1, 0}, {1, 9, 0}), compactDisc("b", {9, 1, 0}, {9, 9, 0}),
                 compactDisc("c", {1, 5, 0}, {2, 5, 0})});
  const CollisionWorld world(c.scenario);
  Path c_path = waitFirst(test::line({1, 5, 0}, {2, 5, 0}, 21), 100);
  Subproblem sub;
  sub.robots = {0, 1};
  sub.t_start = 0;
  sub.t_end = 320;
  LocalSolution local;
  local.paths = {test::line({1, 1, 0}, {1, 9, 0}, 321), test::line({9, 1, 0}, {9, 9, 0}, 161)};
  while (local.paths[1].size() < 321) local.paths[1].push(local.paths[1].back());
  std::vector<Path> paths{local.paths[0], local.paths[1], c_path};
  REQUIRE(c.valid(paths));
  const LocalSolution before = local;
  const std::int64_t saved = retimeLocalSolution(sub, local, c.models.raw, paths, world, Deadline());
  REQUIRE(local.length() == 321);
  CHECK(local.paths[1] == before.paths[1]);  // b had nothing to save
  // a arrives sooner than at half speed, but no sooner than c lets it:
  // it must wait below (1, 5) until c has left.
  Path a = local.paths[0];
  a.dropTrailingWaits();
  CHECK(saved == static_cast<std::int64_t>(320 - (a.size() - 1)));
  CHECK(a.size() < 321);
  CHECK(a.size() > 161 + 30);
  CHECK(routeOf(a) != routeOf(before.paths[0]));  // at full speed where it moves
  CHECK(a.back()[1] == 9.0);
  paths[0] = local.paths[0];
  CHECK(c.valid(paths));
}

namespace {

// 16 mobile robots among 12 obstacles (generated, seed 3).
Scenario sixteenRobots() {
  gen::MobileSettings ms;
  ms.robots = 16;
  ms.obstacles = 12;
  ms.seed = 3;
  return gen::generateMobile(ms);
}

// The same plan every time, under sanitizers too.
PlannerSettings repeatable() {
  PlannerSettings settings;
  settings.work_budgets = true;
  settings.time_limit_s = 60;
  return settings;
}

}  // namespace

TEST_CASE("ARC retimes its answers inside their windows only when asked, and the plan validates") {
  const Scenario s = sixteenRobots();
  PlannerSettings settings = repeatable();
  settings.arc.restamp_coupled = false;  // it would take what retiming saves
  const PlanResult plain = plan(s, settings);
  REQUIRE(plain.solution.solved);
  REQUIRE(plain.stats.arc);
  CHECK_FALSE(plain.stats.arc->window_retimed.has_value());
  settings.arc.retime_windows = true;
  const PlanResult retimed = plan(s, settings);
  REQUIRE(retimed.solution.solved);  // plan() validates it
  REQUIRE(retimed.stats.arc->window_retimed.has_value());
  CHECK(*retimed.stats.arc->window_retimed > 0);
}

namespace {

std::size_t arrivalStep(Path p) {
  p.dropTrailingWaits();
  return p.size() - 1;
}

// a creeps 0.8 from (4.2, 5) towards b's start while b drives 4 up and out
// of its way, then a drives 4 along y = 5 while b waits: in lockstep a
// arrives at step 160, b at 80.
LocalSolution lockstepAnswer(const std::vector<const RobotModel*>& ab) {
  const std::vector<std::vector<std::vector<double>>> waypoints{
      {{4.2, 5, 0}, {5, 5, 0}}, {{5, 5, 0}, {5, 9, 0}}, {{9, 5, 0}, {5, 9, 0}}};
  return timeStampComposite(ab, waypoints);
}

Subproblem wholeSpan(std::size_t robots, std::size_t length) {
  Subproblem sub;
  for (std::size_t r = 0; r < robots; ++r) sub.robots.push_back(static_cast<int>(r));
  sub.t_start = 0;
  sub.t_end = length - 1;
  return sub;
}

}  // namespace

TEST_CASE("A coupled answer time-stamped robot by robot stays valid and no robot arrives later") {
  CompactCase c({compactDisc("a", {4.2, 5, 0}, {9, 5, 0}), compactDisc("b", {5, 5, 0}, {5, 9, 0})});
  const CollisionWorld world(c.scenario);
  LocalSolution local = lockstepAnswer(c.models.raw);
  REQUIRE(local.length() == 161);
  // (Interpolating between b's equal states in the second motion can move
  // it by rounding, which counts as steps of arrival.)
  const std::size_t a_lockstep = arrivalStep(local.paths[0]), b_lockstep = arrivalStep(local.paths[1]);
  REQUIRE(a_lockstep == 160);
  REQUIRE(b_lockstep >= 80);
  REQUIRE(c.valid(local.paths));
  const LocalSolution before = local;
  const Subproblem sub = wholeSpan(2, local.length());
  const std::vector<Path> plan = local.paths;
  const RestampReport rep = restampLocalSolution(sub, local, c.models.raw, plan, world, Deadline());
  REQUIRE(rep.restamped);
  CHECK(c.valid(local.paths));
  CHECK(local.length() <= before.length());
  const std::size_t a = arrivalStep(local.paths[0]), b = arrivalStep(local.paths[1]);
  CHECK(b <= b_lockstep);
  // a at full speed needs 96 steps for its 4.8; b, which drives at full
  // speed already, keeps it from starting at once (a first, b would have
  // met it leaving its start: the order with b first is what was kept).
  CHECK(a < 160);
  CHECK(a > 96);
  CHECK(b == 80);
  CHECK(rep.steps_saved == static_cast<std::int64_t>(160 - a + b_lockstep - b));
}

TEST_CASE("A coupled answer stays in lockstep when its robots find no timing in time") {
  CompactCase c({compactDisc("a", {4.2, 5, 0}, {9, 5, 0}), compactDisc("b", {5, 5, 0}, {5, 9, 0})});
  const CollisionWorld world(c.scenario);
  LocalSolution local = lockstepAnswer(c.models.raw);
  const std::vector<Path> plan = local.paths;
  const LocalSolution before = local;
  const RestampReport rep =
      restampLocalSolution(wholeSpan(2, local.length()), local, c.models.raw, plan, world, Deadline(0.0));
  CHECK_FALSE(rep.restamped);
  CHECK(rep.steps_saved == 0);
  CHECK(local.paths == before.paths);
}

TEST_CASE("A coupled answer keeps its robots clear of the robots outside when it can") {
  // c, outside the group, crosses y = 5 at x = 7 going up over steps
  // 20-60: a at full speed would meet it; the answer avoids it.
  CompactCase c({compactDisc("a", {4.2, 5, 0}, {9, 5, 0}), compactDisc("b", {5, 5, 0}, {5, 9, 0}),
                 compactDisc("c", {7, 3, 0}, {7, 7, 0})});
  const CollisionWorld world(c.scenario);
  RobotModels group(compactScenario({c.scenario.robots[0], c.scenario.robots[1]}));
  LocalSolution local = lockstepAnswer(group.raw);
  Path c_path(3);
  for (int k = 0; k < 20; ++k) c_path.push(std::vector<double>{7, 3, 0}.data());
  c_path.append(test::line({7, 3, 0}, {7, 7, 0}, 81));
  std::vector<Path> paths{local.paths[0], local.paths[1], c_path};
  const RestampReport rep =
      restampLocalSolution(wholeSpan(2, local.length()), local, c.models.raw, paths, world, Deadline());
  REQUIRE(rep.restamped);
  CHECK(rep.around_outside);
  paths[0] = local.paths[0];
  paths[1] = local.paths[1];
  CHECK(c.valid(paths));
  CHECK(arrivalStep(local.paths[0]) < 160);
}

TEST_CASE("ARC with coupled answers time-stamped robot by robot plans valid plans") {
  const Scenario s = sixteenRobots();
  PlannerSettings settings = repeatable();
  settings.arc.restamp_coupled = false;
  const PlanResult lockstep = plan(s, settings);
  REQUIRE(lockstep.solution.solved);
  CHECK_FALSE(lockstep.stats.arc->coupled_restamped.has_value());
  settings.arc.restamp_coupled = true;
  const PlanResult restamped = plan(s, settings);
  REQUIRE(restamped.solution.solved);  // plan() validates it
  const ArcStats& st = *restamped.stats.arc;
  REQUIRE(st.coupled_restamped.has_value());
  CHECK(*st.coupled_restamped > 0);
  CHECK(*st.restamped_steps > 0);
  CHECK(*st.coupled_restamped + *st.coupled_lockstep == st.subproblems_by_solver.at("coupled"));
}

TEST_CASE("ARC compacts its valid plan, and no robot arrives later for it") {
  const Scenario s = sixteenRobots();
  PlannerSettings settings = repeatable();
  settings.arc.compact_passes = 0;
  const PlanResult plain = plan(s, settings);
  REQUIRE(plain.solution.solved);
  CHECK_FALSE(plain.stats.arc->compacted_steps.has_value());
  settings.arc.compact_passes = 1;
  const PlanResult compacted = plan(s, settings);
  REQUIRE(compacted.solution.solved);  // plan() validates it
  REQUIRE(compacted.stats.arc->compacted_steps.has_value());
  // The loop is the same: the same conflicts, then the same plan retimed.
  CHECK(compacted.stats.arc->conflicts == plain.stats.arc->conflicts);
  std::int64_t before = 0, after = 0;
  for (std::size_t r = 0; r < s.robots.size(); ++r) {
    const std::size_t a = arrivalStep(plain.solution.paths[r]), b = arrivalStep(compacted.solution.paths[r]);
    CHECK(b <= a);
    before += static_cast<std::int64_t>(a);
    after += static_cast<std::int64_t>(b);
  }
  CHECK(after < before);
  CHECK(*compacted.stats.arc->compacted_steps == before - after);
}
