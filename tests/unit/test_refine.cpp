// Anytime refinement: shortcuts and large-neighbourhood search never make a
// valid plan invalid or costlier, make a wasteful one shorter, and give the
// same plan for the same seed when their budgets count work; a shortcut
// waits for a robot crossing it; the own-path bound bounds valid paths.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/generators.hpp"
#include "earc/io/json_io.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/path_bound.hpp"
#include "earc/planning/planner.hpp"
#include "earc/planning/refine.hpp"
#include "earc/service/service.hpp"
#include "earc/validate/scenario_check.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"

using namespace earc;

namespace {

RobotSpec refineDisc(const std::string& name, std::vector<double> start, std::vector<double> goal) {
  RobotSpec s = RobotSpec::mobileDisc(name, 0.3);
  s.start = std::move(start);
  s.goal = std::move(goal);
  return s;
}

Solution refineSolution(const Scenario& scenario, const std::vector<Path>& paths) {
  Solution sol;
  sol.solved = true;
  sol.paths = paths;
  sol.scenario = scenario.name;
  sol.nameRobots(scenario);
  return sol;
}

bool refineValid(const Scenario& scenario, const std::vector<Path>& paths) {
  const ValidationReport rep = validateSolution(scenario, refineSolution(scenario, paths));
  if (!rep.valid && !rep.violations.empty()) MESSAGE(rep.violations.front().detail);
  return rep.valid;
}

std::size_t refineSoc(const std::vector<Path>& paths) {
  std::size_t s = 0;
  for (const Path& p : paths) s += p.size() - 1;
  return s;
}

std::size_t refineMakespan(const std::vector<Path>& paths) {
  std::size_t m = 0;
  for (const Path& p : paths) m = std::max(m, p.size() - 1);
  return m;
}

// Refines with a budget of work and iterations, nothing of wall-clock time:
// the same result on any machine.
RefineReport refineCounted(const Scenario& s, std::vector<Path>& paths, std::uint64_t seed, std::size_t iterations,
                           bool lns = true) {
  const CollisionWorld world(s);
  const RobotModels models(s);
  RefineSettings rs;
  rs.lns = lns;
  rs.seed = seed;
  rs.seconds = 1000;  // of work (kWorkPerBudgetSecond units a second): never reached here
  rs.max_iterations = iterations;
  return refinePlan(s, world, models.raw, paths, rs, Deadline().withWorkBudgets(true));
}

// `waits` copies of the path's state at step `at` inserted there.
Path refineWaitAt(const Path& p, std::size_t at, int waits) {
  Path out(p.dim());
  for (std::size_t t = 0; t < p.size(); ++t) {
    out.push(p.at(t));
    if (t == at)
      for (int k = 0; k < waits; ++k) out.push(p.at(t));
  }
  return out;
}

// Straight pieces through the given points, each at full speed (steps of
// at most 0.05, the default resolution).
Path refinePolyline(const std::vector<std::vector<double>>& points) {
  Path p(3);
  p.push(points.front().data());
  for (std::size_t i = 1; i < points.size(); ++i) {
    const auto& a = points[i - 1];
    const auto& b = points[i];
    const int n = static_cast<int>(std::ceil(std::hypot(b[0] - a[0], b[1] - a[1]) / 0.05 - 1e-9));
    const Path piece = test::line(a, b, n + 1);
    p.append(piece, 1);
  }
  return p;
}

}  // namespace

TEST_CASE("Refinement makes a detour with needless waits strictly shorter, and keeps clear of a standing robot") {
  for (bool lns : {false, true}) {  // shortcuts alone, and with neighbourhoods
    CAPTURE(lns);
    Scenario s;
    s.name = "refine-detour";
    s.workspace = {{0, 0}, {12, 12}};
    // b stands still in the middle of a's straight way; a detours far
    // around it and waits twice on the way for nothing.
    s.robots = {refineDisc("a", {1, 6, 0}, {11, 6, 0}), refineDisc("b", {6, 6, 0}, {6, 6, 0})};
    Path a = refinePolyline({{1, 6, 0}, {2, 10, 0}, {10, 10, 0}, {11, 6, 0}});
    a = refineWaitAt(refineWaitAt(a, 30, 40), 200, 25);
    std::vector<Path> paths{a, test::line({{6, 6, 0}})};
    REQUIRE(refineValid(s, paths));
    const std::size_t before = refineSoc(paths);
    const RefineReport rep = refineCounted(s, paths, 1, 400, lns);
    CHECK(refineValid(s, paths));
    CHECK(rep.first_sum_of_costs == before);
    CHECK(rep.final_sum_of_costs == refineSoc(paths));
    CHECK(rep.final_sum_of_costs < before);
    // The waits alone are 65 steps; the straight line through b is 200
    // steps, and the way around b's disc is not much longer.
    CHECK(refineSoc(paths) + 65 < before);
    CHECK(refineSoc(paths) < 260);
    CHECK(rep.shortcut_improvements + rep.lns_improvements > 0);
    CHECK(paths[1].size() == 1);  // b had nothing to gain
    CHECK(rep.history.size() == rep.shortcut_improvements + rep.lns_improvements + (rep.retimed_steps > 0 ? 1 : 0));
    for (std::size_t i = 1; i < rep.history.size(); ++i) CHECK(rep.history[i][1] < rep.history[i - 1][1]);
  }
}

TEST_CASE("Refinement never returns an invalid or a costlier plan, on random mobile robots and arms") {
  for (std::uint64_t seed : {1, 2, 3}) {
    gen::MobileSettings ms;
    ms.robots = 8;
    ms.obstacles = 8;
    ms.workspace = 12;
    ms.seed = seed;
    gen::ArmSettings as;
    as.robots = 4;
    as.obstacles = gen::defaultArmObstacles(4);
    as.seed = seed;
    for (const Scenario& s : {gen::generateMobile(ms), gen::generateArms(as)}) {
      CAPTURE(s.name);
      PlannerSettings settings;
      settings.method = Method::Prioritized;
      settings.time_limit_s = 60;
      settings.seed = seed;
      const PlanResult first = plan(s, settings);
      if (!first.solution.solved) continue;
      std::vector<Path> paths = first.solution.paths;
      const std::size_t soc = refineSoc(paths), makespan = refineMakespan(paths);
      const RefineReport rep = refineCounted(s, paths, seed, 60);
      CHECK(refineValid(s, paths));
      CHECK(refineSoc(paths) <= soc);
      CHECK(refineMakespan(paths) <= makespan);
      CHECK(rep.final_sum_of_costs == refineSoc(paths));
      CHECK(rep.final_makespan == refineMakespan(paths));
      CHECK(rep.lower_bound <= refineSoc(paths));
      for (std::size_t r = 0; r < paths.size(); ++r) {
        CHECK(std::equal(paths[r].at(0), paths[r].at(0) + paths[r].dim(), first.solution.paths[r].at(0)));
        CHECK(std::equal(paths[r].back(), paths[r].back() + paths[r].dim(), first.solution.paths[r].back()));
      }
    }
  }
}

TEST_CASE("Refinement with the same seed and counted budgets gives the same plan") {
  gen::MobileSettings ms;
  ms.robots = 10;
  ms.obstacles = 6;
  ms.workspace = 12;
  ms.seed = 5;
  const Scenario s = gen::generateMobile(ms);
  PlannerSettings settings;
  settings.method = Method::Prioritized;
  const PlanResult first = plan(s, settings);
  REQUIRE(first.solution.solved);
  std::vector<Path> one = first.solution.paths, two = first.solution.paths;
  const RefineReport a = refineCounted(s, one, 7, 80);
  const RefineReport b = refineCounted(s, two, 7, 80);
  CHECK(one == two);
  CHECK(a.final_sum_of_costs == b.final_sum_of_costs);
  CHECK(a.iterations == b.iterations);
  CHECK(a.lns_tries == b.lns_tries);
  CHECK(a.shortcut_improvements == b.shortcut_improvements);
  CHECK(a.final_sum_of_costs < a.first_sum_of_costs);  // there was something to refine
}

TEST_CASE("Refinement through plan(): the stats say what it did and the plan returned validates") {
  gen::MobileSettings ms;
  ms.robots = 8;
  ms.obstacles = 6;
  ms.workspace = 12;
  ms.seed = 4;
  const Scenario s = gen::generateMobile(ms);
  PlannerSettings settings;
  settings.method = Method::Arc;
  settings.work_budgets = true;
  settings.post.refine_s = 0.3;
  const PlanResult r = plan(s, settings);
  REQUIRE(r.solution.solved);
  REQUIRE(r.stats.refine);
  const RefineStats& st = *r.stats.refine;
  CHECK_FALSE(st.rejected);
  CHECK(st.final_sum_of_costs == r.stats.sum_of_costs);
  CHECK(st.final_makespan == r.stats.makespan);
  CHECK(st.final_sum_of_costs <= st.first_sum_of_costs);
  CHECK(st.first_s == r.stats.planning_time_s);
  CHECK(st.final_s >= st.first_s);
  REQUIRE(st.history.size() >= 1);
  CHECK(st.history[0].sum_of_costs == st.first_sum_of_costs);
  CHECK(st.history.back().sum_of_costs == st.final_sum_of_costs);
  CHECK(st.seconds_spent >= 0);
  CHECK(refineValid(s, r.solution.paths));
  // Off by default: no stats, the plan as planned.
  settings.post.refine_s = 0;
  CHECK_FALSE(plan(s, settings).stats.refine);
}

TEST_CASE("serve protocol: \"refine\" refines a request's plan, and a bad value is refused in one line") {
  service::Service svc(nullptr, {});
  const std::string file = EARC_SOURCE_DIR "/datasets/mobile-obst-16-s1.json";
  for (const nlohmann::json& bad : {nlohmann::json(-1), nlohmann::json("1"), nlohmann::json(true)}) {
    const auto r = nlohmann::json::parse(
        svc.handleLine(nlohmann::json{{"scenario_file", file}, {"method", "prioritized"}, {"refine", bad}}.dump()));
    CHECK(r["ok"] == false);
    CHECK(r["error"].get<std::string>().find("$.refine: must be a number of seconds >= 0") != std::string::npos);
  }
  const auto r = nlohmann::json::parse(svc.handleLine(
      nlohmann::json{{"scenario_file", file}, {"method", "prioritized"}, {"refine", 0.5}}.dump()));
  REQUIRE(r["solved"] == true);
  REQUIRE(r["stats"].contains("refine"));
  CHECK(r["stats"]["sum_of_costs"] == r["stats"]["refine"]["final_sum_of_costs"]);
  CHECK(r["stats"]["sum_of_costs"] <= r["stats"]["refine"]["first_sum_of_costs"]);
  const Scenario scenario = loadScenario(file);
  CHECK(validateSolution(scenario, solutionFromJson(r["solution"], &scenario, "response")).valid);
  svc.close();
}

TEST_CASE("A robot's own shortest way around a wall bounds its plans, and is the straight line without obstacles") {
  Scenario s;
  s.name = "bound-wall";
  s.workspace = {{0, 0}, {12, 12}};
  s.obstacles = {Obstacle::makeBox({6, 6}, {1, 8})};  // x 5.5..6.5, y 2..10
  s.robots = {refineDisc("a", {2, 6, 0}, {10, 6, 0}), refineDisc("b", {2, 11, 0}, {10, 11, 0})};
  const RobotModels models(s);
  const std::vector<std::size_t> straight = straightLineBounds(s, models.raw);
  const std::vector<std::size_t> own = ownPathLowerBounds(s, models.raw);
  CHECK(straight == std::vector<std::size_t>{160, 160});
  // a goes round an end of the wall: at least to y = 10 and back, about 11 m.
  CHECK(own[0] > 210);
  CHECK(own[1] == 160);  // b's straight way passes the wall's end
  // A valid way round it is no shorter than the bound.
  const Path around = refinePolyline({{2, 6, 0}, {5.15, 10.35, 0}, {6.85, 10.35, 0}, {10, 6, 0}});
  Scenario one = s;
  one.robots = {s.robots[0]};
  REQUIRE(refineValid(one, {around}));
  CHECK(own[0] <= around.size() - 1);
  CHECK(own[0] + 40 > around.size() - 1);  // and not far below it
  // Beyond max_obstacles, and with no obstacles: the straight line.
  CHECK(ownPathLowerBounds(s, models.raw, 0) == straight);
  s.obstacles.clear();
  CHECK(ownPathLowerBounds(s, models.raw) == straight);
}

TEST_CASE("A shortcut across a robot's way is kept with waits until the robot has passed") {
  Scenario s;
  s.name = "refine-crossing";
  s.workspace = {{0, 0}, {12, 12}};
  // b crosses a's straight way just when a would get there at full speed;
  // a's plan goes round below, behind b.
  s.robots = {refineDisc("a", {1, 6, 0}, {11, 6, 0}), refineDisc("b", {6, 1, 0}, {6, 11, 0})};
  std::vector<Path> paths{refinePolyline({{1, 6, 0}, {1, 2.5, 0}, {11, 2.5, 0}, {11, 6, 0}}),
                          refinePolyline({{6, 1, 0}, {6, 11, 0}})};
  REQUIRE(refineValid(s, paths));
  const std::size_t before = paths[0].size() - 1;
  const CollisionWorld world(s);
  const RobotModels models(s);
  RefineSettings rs;
  rs.lns = false;
  rs.seed = 3;
  rs.seconds = 1000;  // of work: never reached here
  rs.max_iterations = 300;
  const RefineReport rep = refinePlan(s, world, models.raw, paths, rs, Deadline().withWorkBudgets(true));
  CHECK(refineValid(s, paths));
  CHECK(rep.final_sum_of_costs == paths[0].size() - 1 + paths[1].size() - 1);
  CHECK(paths[1].size() - 1 == 200);  // b was on its straight way already
  // a goes nearly straight (200 steps), waiting a little for b.
  CHECK(paths[0].size() - 1 < before);
  CHECK(paths[0].size() - 1 <= 240);
  std::size_t waits = 0;
  for (std::size_t t = 0; t + 1 < paths[0].size(); ++t)
    waits += std::equal(paths[0].at(t), paths[0].at(t) + 3, paths[0].at(t + 1)) ? 1 : 0;
  CHECK(waits > 0);  // it let b pass
  CHECK(rep.lower_bound == 400);
  CHECK(rep.straight_line_bound == 400);
}
