// ARC: splicing, merging, and whole plans that must validate.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/generators.hpp"
#include "earc/methods/plan.hpp"
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

TEST_CASE("Splicing replaces the window and shifts the rest of the path in time") {
  Path p = line({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {4, 0, 0}});
  std::vector<Path> paths{p};
  Subproblem sub;
  sub.robots = {0};
  sub.t_start = 1;
  sub.t_end = 3;
  LocalSolution local;
  local.paths = {line({{1, 0, 0}, {1, 0, 0}, {1.5, 0, 0}, {2, 0, 0}, {2.5, 0, 0}, {3, 0, 0}})};
  splice(paths, sub, local);
  // One state before the window, six local states, one after.
  REQUIRE(paths[0].size() == 8);
  CHECK(paths[0].at(0)[0] == 0);
  CHECK(paths[0].at(2)[0] == 1);
  CHECK(paths[0].at(6)[0] == 3);
  CHECK(paths[0].at(7)[0] == 4);  // the old suffix, three steps later
}

TEST_CASE("Splicing a robot that had already finished pads its path with waits first") {
  std::vector<Path> paths{line({{0, 0, 0}, {1, 0, 0}})};
  Subproblem sub;
  sub.robots = {0};
  sub.t_start = 4;
  sub.t_end = 6;
  LocalSolution local;
  local.paths = {line({{1, 0, 0}, {1, 1, 0}, {1, 0, 0}})};
  splice(paths, sub, local);
  REQUIRE(paths[0].size() == 7);
  CHECK(paths[0].at(4)[1] == 0);
  CHECK(paths[0].at(5)[1] == 1);
  CHECK(paths[0].at(6)[1] == 0);
}

TEST_CASE("Merging pulls in the robots of resolved spans that overlap in time and share a conflict robot") {
  std::vector<ResolvedSpan> spans{{{1, 4}, 10, 30}, {{4, 7}, 25, 40}, {{2, 9}, 0, 100}, {{1, 5}, 50, 60}};
  std::vector<int> robots{1, 3};
  int added = mergeOverlapping(robots, spans, 20, 28, 8);
  // {1,4} overlaps and shares 1 -> 4. {4,7} overlaps but shares only the
  // merged 4 (one hop, not transitive); {2,9} shares nothing; {1,5} is
  // later in time.
  CHECK(robots == std::vector<int>{1, 3, 4});
  CHECK(added == 1);
}

TEST_CASE("Merging skips a span that would make the group larger than the cap") {
  std::vector<ResolvedSpan> spans{{{1, 4, 5, 6}, 10, 30}, {{3, 8}, 10, 30}};
  std::vector<int> robots{1, 3};
  int added = mergeOverlapping(robots, spans, 20, 20, 4);
  CHECK(robots == std::vector<int>{1, 3, 8});
  CHECK(added == 1);
}

TEST_CASE("ARC plans four discs crossing in the open, and the solution validates") {
  Scenario s = openScenario(6);
  s.robots = {disc("w", 0.3, {1, 3, 0}, {5, 3, 0}), disc("e", 0.3, {5, 3, 3.14}, {1, 3, 0}),
              disc("s", 0.3, {3, 1, 1.57}, {3, 5, 0}), disc("n", 0.3, {3, 5, -1.57}, {3, 1, 0})};
  PlannerSettings settings;
  settings.time_limit_s = 30;
  settings.seed = 3;
  PlanResult r = plan(s, settings);
  REQUIRE(r.solution.solved);
  CHECK(r.failures.empty());
  CHECK(r.stats.arc->conflicts >= 1);
  ValidationReport v = validateSolution(s, r.solution);
  CHECK(v.valid);
}

TEST_CASE("A roadmap built when a solver first asks for it is counted apart from that solver's time") {
  // Two discs whose straight motions meet head-on: no roadmap for their
  // own paths; the decoupled solver builds the shared one for the conflict.
  Scenario s = openScenario(6);
  s.robots = {disc("w", 0.3, {1, 3, 0}, {5, 3, 0}), disc("e", 0.3, {5, 3, 3.14}, {1, 3, 0})};
  PlannerSettings settings;
  settings.seed = 2;
  settings.trace = true;
  PlanResult r = plan(s, settings);
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(s, r.solution).valid);
  CHECK(r.stats.arc->roadmaps_built == 1);
  const double building = r.stats.arc->roadmap_build_s;
  CHECK(building > 0);
  // The attempt that built it says so, and its time_s leaves it out.
  double in_attempts = 0;
  for (const auto& e : r.trace["events"])
    if (e["type"] == "subproblem")
      for (const auto& a : e["attempts"]) in_attempts += a.value("roadmap_build_s", 0.0);
  CHECK(in_attempts == doctest::Approx(building));
  double solver_time = 0;
  for (const auto& [name, secs] : r.stats.arc->solver_time_s) solver_time += secs;
  CHECK(solver_time + building <= *r.stats.planning_time_s);
}

TEST_CASE("ARC keeps trying a conflict that grew to the whole problem until the deadline, then says both why") {
  // Two discs must swap ends of a corridor too narrow to pass: no
  // subproblem can ever be solved. ARC must not give up early with time
  // left (it retries the whole problem with growing budgets), and must
  // report the time limit and the unsolved subproblem.
  Scenario s;
  s.name = "corridor";
  s.workspace = {{0, 0}, {6, 1}};
  s.robots = {disc("a", 0.3, {0.5, 0.5, 0}, {5.5, 0.5, 0}), disc("b", 0.3, {5.5, 0.5, 0}, {0.5, 0.5, 0})};
  PlannerSettings settings;
  settings.time_limit_s = 5.0;
  settings.arc.max_expansions = 3;  // 64 steps each side: the whole 100-step paths
  PlanResult r = plan(s, settings);
  CHECK_FALSE(r.solution.solved);
  CHECK(r.failures.count(FailureCause::TimeLimit) == 1);
  CHECK(r.failures.count(FailureCause::SubproblemUnsolved) == 1);
  CHECK(*r.stats.planning_time_s >= 4.9);
  CHECK(r.stats.arc->subproblems > settings.arc.max_expansions + 1);  // retried beyond the last level
  // Every window after the first was an expansion, though none solved.
  CHECK(r.stats.arc->window_expansions == r.stats.arc->subproblems - 1);
}

TEST_CASE("A solver answering with the wrong number of paths is a named error, not a corrupted plan") {
  // A buggy solver: one path for a two-robot subproblem.
  struct OnePath : SubproblemSolver {
    const char* name() const override { return "one-path"; }
    SolverOutcome solve(SolverContext& ctx) override {
      LocalSolution sol;
      sol.paths.push_back(line({ctx.sub.starts[0], ctx.sub.goals[0]}));
      return {std::move(sol), name(), -1};
    }
  };
  Scenario s = openScenario(6);
  s.robots = {disc("w", 0.3, {1, 3, 0}, {5, 3, 0}), disc("e", 0.3, {5, 3, 3.14}, {1, 3, 0})};
  PlannerSettings settings;
  settings.time_limit_s = 10;
  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy;
  hierarchy.push_back(std::make_unique<OnePath>());
  CHECK_THROWS_WITH_AS(runArc(s, settings, {}, std::move(hierarchy)),
                       doctest::Contains("solver 'one-path' answered a subproblem of 2 robots with 1 paths"),
                       std::logic_error);
}

TEST_CASE("ARC's retries beyond the last level ignore the robots outside the group every other time") {
  // A solver that records what each attempt was told, and solves only when
  // told to ignore the other robots (as a group walled in by them would).
  struct Recorder : SubproblemSolver {
    std::vector<std::pair<bool, bool>>* seen;  // (whole problem, ignore others) per attempt
    explicit Recorder(std::vector<std::pair<bool, bool>>* s) : seen(s) {}
    const char* name() const override { return "recorder"; }
    SolverOutcome solve(SolverContext& ctx) override {
      seen->emplace_back(ctx.sub.whole_problem, ctx.ignore_others);
      if (!ctx.ignore_others) return {std::nullopt, name(), -1};
      return DecoupledSolver().solve(ctx);
    }
  };
  Scenario s = openScenario(6);
  s.robots = {disc("w", 0.3, {1, 3, 0}, {5, 3, 0}), disc("e", 0.3, {5, 3, 3.14}, {1, 3, 0}),
              disc("n", 0.3, {0.5, 5.5, 0}, {0.6, 5.5, 0})};
  PlannerSettings settings;
  settings.time_limit_s = 20;
  settings.arc.max_expansions = 2;
  settings.arc.initial_window = 64;  // the window spans the paths: level 2 is the whole problem
  settings.arc.crowd_fallback = false;  // ARC's own retries, not a jam handed over
  std::vector<std::pair<bool, bool>> seen;
  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy;
  hierarchy.push_back(std::make_unique<Recorder>(&seen));
  PlanResult r = runArc(s, settings, {}, std::move(hierarchy));
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(s, r.solution).valid);
  // Levels 0 to 2 (the last a whole problem) without ignoring, the first
  // retry beyond them ignoring, and solved there.
  REQUIRE(seen.size() >= 4);
  for (std::size_t i = 0; i + 1 < seen.size(); ++i) CHECK_FALSE(seen[i].second);
  CHECK(seen.back().first);
  CHECK(seen.back().second);
}

TEST_CASE("A conflict's merge cap grows by one robot every third time it comes back, up to four more") {
  ConflictRecurrence rec;
  std::vector<std::size_t> caps;
  // The same two robots in the same half-unit cell, at drifting instants:
  // every resolution shifts the later paths in time.
  for (int i = 0; i < 16; ++i) caps.push_back(rec.capFor({3, 7, 41.5 + 3 * i, {2.1 + 0.02 * i, 3.2}}, 5));
  CHECK(caps == std::vector<std::size_t>{5, 5, 5, 6, 6, 6, 7, 7, 7, 8, 8, 8, 9, 9, 9, 9});
  // Another cell, or another pair, is another conflict.
  CHECK(rec.capFor({3, 7, 41.5, {2.6, 3.2}}, 5) == 5);
  CHECK(rec.capFor({3, 7, 41.5, {2.1, 2.9}}, 5) == 5);
  CHECK(rec.capFor({3, 8, 41.5, {2.1, 3.2}}, 5) == 5);
  CHECK(rec.capFor({7, 3, 41.5, {2.1, 3.2}}, 2) == 6);  // the same pair either way round
}

TEST_CASE("Groups at the merge cap that undo each other grow until the plan is solved, instead of looping") {
  // Every solver here plans its group as if no other robot were there, as
  // the coupled solver does; with groups capped at two robots, each
  // answer runs into a robot of another group and undoes its resolution.
  // Eight 0.8-radius discs in an 8 x 8 square: with the cap fixed, this
  // plan looped until its 30 s limit; a conflict that comes back now takes
  // in the robot it keeps running into.
  struct Blinkered : SubproblemSolver {
    const char* name() const override { return "blinkered"; }
    SolverOutcome solve(SolverContext& ctx) override {
      ctx.ignore_others = true;
      return DecoupledSolver().solve(ctx);
    }
  };
  gen::MobileSettings crowd;
  crowd.robots = 8;
  crowd.workspace = 8;
  crowd.footprint.shape = MobileShape::Disc;
  crowd.footprint.radius = 0.8;
  crowd.seed = 5;
  const Scenario s = gen::generateMobile(crowd);
  PlannerSettings settings;
  settings.time_limit_s = 30;
  settings.arc.crowd_fallback = false;  // the merge cap as published, not a jam handed over
  settings.arc.max_merged_robots = 2;
  settings.work_budgets = true;  // the same plan under sanitizers
  settings.trace = true;
  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy;
  hierarchy.push_back(std::make_unique<Blinkered>());
  PlanResult r = runArc(s, settings, {}, std::move(hierarchy));
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(s, r.solution).valid);
  CHECK(r.stats.arc->merge_cap_raised > 0);
  // A group past the cap only where the trace says its cap was raised.
  std::size_t largest = 0;
  for (const auto& ev : r.trace["events"]) {
    if (ev["type"] != "subproblem") continue;
    const std::size_t n = ev["robots"].size();
    largest = std::max(largest, n);
    if (n > 2) CHECK(ev.contains("merge_cap"));
  }
  CHECK(largest > 2);
}

TEST_CASE("ARC plans two facing arms whose straight motions collide, and the solution validates") {
  Scenario s;
  s.name = "arms";
  s.workspace = {{-4, -4}, {4, 8}};
  // Bases 4 apart facing each other; both reach for the middle and swap sides.
  s.robots = {fiveLinkArm("a", {0, 0}, 1.5708, {0.9, 0, 0, 0, 0}, {-0.9, 0, 0, 0, 0}),
              fiveLinkArm("b", {0, 4}, -1.5708, {0.9, 0, 0, 0, 0}, {-0.9, 0, 0, 0, 0})};
  PlannerSettings settings;
  settings.time_limit_s = 30;
  settings.seed = 5;
  PlanResult r = plan(s, settings);
  REQUIRE(r.solution.solved);
  ValidationReport v = validateSolution(s, r.solution);
  CHECK(v.valid);
}


TEST_CASE("Every method reports a solution as solved only when it validates") {
  Scenario s = openScenario(6);
  s.robots = {disc("a", 0.3, {1, 1, 0}, {5, 5, 0}), disc("b", 0.3, {5, 5, 0}, {1, 1, 0})};
  for (Method m : {Method::Arc, Method::Prioritized, Method::Coupled}) {
    CAPTURE(methodName(m));
    PlannerSettings settings;
    settings.method = m;
    settings.time_limit_s = 20;
    PlanResult r = plan(s, settings);
    REQUIRE(r.solution.solved);
    CHECK(validateSolution(s, r.solution).valid);
    CHECK(r.solution.method == methodName(m));
  }
}

TEST_CASE("A solution's paths end where each robot last moves, so sum of costs is not n x makespan") {
  // The prioritized baseline padded every path to the makespan: a robot
  // with a short trip was charged for waiting at its goal.
  Scenario s = openScenario(8);
  s.robots = {disc("near", 0.3, {1, 1, 0}, {2, 1, 0}), disc("far", 0.3, {1, 3, 0}, {7, 7, 0})};
  for (Method m : {Method::Arc, Method::Prioritized, Method::Coupled}) {
    CAPTURE(std::string(methodName(m)));
    PlannerSettings settings;
    settings.method = m;
    settings.time_limit_s = 20;
    PlanResult r = plan(s, settings);
    REQUIRE(r.solution.solved);
    for (const Path& p : r.solution.paths) {
      REQUIRE(p.size() >= 2);
      CHECK_FALSE(std::equal(p.at(p.size() - 1), p.at(p.size() - 1) + p.dim(), p.at(p.size() - 2)));
    }
    // Coupled planning moves every robot along each composite edge, so
    // the near robot creeps until the end; the others plan each robot alone.
    if (m == Method::Coupled) continue;
    CHECK(r.solution.paths[0].size() < r.solution.paths[1].size());
    CHECK(*r.stats.sum_of_costs < 2 * *r.stats.makespan);
  }
}

TEST_CASE("Dropping a path's trailing waits keeps every state up to its last move") {
  Path p = line({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 0, 0}, {2, 0, 0}});
  p.dropTrailingWaits();
  CHECK(p == line({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 0, 0}}));
  Path still = line({{3, 3, 1}, {3, 3, 1}});
  still.dropTrailingWaits();
  CHECK(still == line({{3, 3, 1}}));
  Path turn = line({{3, 3, 1}, {3, 3, 1.5}});
  turn.dropTrailingWaits();
  CHECK(turn.size() == 2);
}

namespace {

// The decoupled solver's answers, each robot then waiting `pad` more steps
// at its window goal, as a group whose slowest robot arrives later would.
struct PaddedDecoupled : SubproblemSolver {
  std::size_t pad;
  explicit PaddedDecoupled(std::size_t p) : pad(p) {}
  const char* name() const override { return "decoupled"; }
  SolverOutcome solve(SolverContext& ctx) override {
    SolverOutcome out = DecoupledSolver().solve(ctx);
    if (out.solution)
      for (Path& p : out.solution->paths)
        for (std::size_t k = 0; k < pad; ++k) p.push(p.back());
    return out;
  }
};

Scenario longCrossing() {
  // Two discs crossing the middle of a 20 m square, their paths far longer
  // than a window, so the window goals lie midway along them.
  Scenario s = openScenario(20);
  s.robots = {disc("w", 0.3, {1, 10, 0}, {19, 10.2, 0}), disc("e", 0.3, {19, 10, 3.14}, {1, 9.8, 3.14})};
  return s;
}

}  // namespace

TEST_CASE("A group's robots go on from their window goals when they reach them, not at the group's last step") {
  const Scenario s = longCrossing();
  PlannerSettings settings;
  settings.time_limit_s = 20;
  settings.arc.crowd_fallback = false;
  auto run = [&](std::size_t pad) {
    std::vector<std::unique_ptr<SubproblemSolver>> hierarchy;
    hierarchy.push_back(std::make_unique<PaddedDecoupled>(pad));
    return runArc(s, settings, {}, std::move(hierarchy));
  };
  const PlanResult plain = run(0);
  const PlanResult padded = run(25);
  REQUIRE(plain.solution.solved);
  REQUIRE(padded.solution.solved);
  CHECK(validateSolution(s, padded.solution).valid);
  REQUIRE(plain.stats.arc->subproblems >= 1);
  // Every padded wait is left out: the same paths as without padding.
  CHECK(padded.solution.paths == plain.solution.paths);
  CHECK(*padded.stats.arc->waits_left_out >=
        *plain.stats.arc->waits_left_out + 25 * 2 * plain.stats.arc->subproblems);
}

TEST_CASE("A small fleet's failed window goes to ARC's next window, not to the crowd solver") {
  // A solver that fails its first subproblem once: in a fleet of six, a jam
  // would be the whole fleet, so ARC expands the window instead.
  struct FailsOnce : SubproblemSolver {
    int calls = 0;
    const char* name() const override { return "decoupled"; }
    SolverOutcome solve(SolverContext& ctx) override {
      if (calls++ == 0) return {std::nullopt, name(), -1};
      return DecoupledSolver().solve(ctx);
    }
  };
  Scenario s = openScenario(8);
  s.robots = {disc("w", 0.3, {1, 4, 0}, {7, 4, 0}), disc("e", 0.3, {7, 4, 3.14}, {1, 4, 3.14}),
              disc("a", 0.3, {1, 1, 0}, {2, 1, 0}), disc("b", 0.3, {7, 1, 0}, {6, 1, 0}),
              disc("c", 0.3, {1, 7, 0}, {2, 7, 0}), disc("d", 0.3, {7, 7, 0}, {6, 7, 0})};
  PlannerSettings settings;
  settings.time_limit_s = 20;
  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy;
  hierarchy.push_back(std::make_unique<FailsOnce>());
  const PlanResult r = runArc(s, settings, {}, std::move(hierarchy));
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(s, r.solution).valid);
  CHECK(r.stats.arc->crowd_handovers.empty());
  CHECK(r.stats.arc->window_expansions >= 1);
}
