// E-ARC: the database solver in ARC's hierarchy, learning, translation to
// the conflict, and repair.
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "earc/collision/collision_world.hpp"
#include "earc/experience/retrieval.hpp"
#include "earc/experience/store.hpp"
#include "earc/io/input_error.hpp"
#include "earc/methods/database_solver.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/composite.hpp"
#include "earc/planning/coupled_solver.hpp"
#include "earc/planning/planner.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"

using earc::test::line;
using earc::test::TempDb;

using namespace earc;
namespace fs = std::filesystem;

namespace {

RobotSpec disc(const std::string& name, std::vector<double> start, std::vector<double> goal) {
  RobotSpec s;
  s.name = name;
  s.kind = RobotKind::Mobile;
  s.shape = MobileShape::Disc;
  s.radius = 0.3;
  s.start = std::move(start);
  s.goal = std::move(goal);
  return s;
}

// Four discs that cross at the centre of a 6 x 6 square, offset by (dx, dy).
Scenario crossing(double dx, double dy, double size) {
  Scenario s;
  s.name = "crossing";
  s.workspace = {{0, 0}, {size, size}};
  s.robots = {disc("w", {1 + dx, 3 + dy, 0}, {5 + dx, 3 + dy, 0}), disc("e", {5 + dx, 3 + dy, 3.14}, {1 + dx, 3 + dy, 0}),
              disc("s", {3 + dx, 1 + dy, 1.57}, {3 + dx, 5 + dy, 0}), disc("n", {3 + dx, 5 + dy, -1.57}, {3 + dx, 1 + dy, 0})};
  return s;
}

PlannerSettings earcSettings(std::uint64_t seed) {
  PlannerSettings p;
  p.method = Method::Earc;
  p.time_limit_s = 30;
  p.seed = seed;
  return p;
}

// Robots 0 and 1 from starts to goals within one step, in the box
// (1, 1)-(9, 9) of a 10 x 10 world, headings free.
Subproblem pairSubproblem(std::vector<std::vector<double>> starts, std::vector<std::vector<double>> goals) {
  Subproblem sub;
  sub.robots = {0, 1};
  sub.starts = std::move(starts);
  sub.goals = std::move(goals);
  for (int r = 0; r < 2; ++r) sub.region.push_back({{1, 1, -3.15}, {9, 9, 3.15}});
  sub.workspace_region = {{1, 1}, {9, 9}};
  sub.t_start = 0;
  sub.t_end = 1;
  return sub;
}

}  // namespace

TEST_CASE("E-ARC learns the subproblems it solved from scratch and solves them from the database next time") {
  TempDb tmp;
  Scenario s = crossing(0, 0, 6);
  int learned = 0;
  {
    exp::ExperienceStore store(tmp.file());
    PlannerSettings traced = earcSettings(1);
    traced.trace = true;
    PlanResult first = plan(s, traced, &store);
    REQUIRE(first.solution.solved);
    CHECK(validateSolution(s, first.solution).valid);
    CHECK(*first.stats.db_hits == 0);  // the store was empty
    // ... and the trace says so for the database's attempts.
    int explained = 0;
    for (const auto& ev : first.trace["events"])
      if (ev["type"] == "subproblem")
        for (const auto& a : ev["attempts"])
          if (a["solver"] == "database") {
            CHECK_FALSE(a["ok"].get<bool>());
            CHECK(a.value("detail", "") == "no entries of this class");
            ++explained;
          }
    CHECK(explained >= 1);
    learned = first.stats.db->db_learned;
    CHECK(learned >= 1);
    CHECK(store.size() == static_cast<std::size_t>(learned));
  }
  exp::ExperienceStore store(tmp.file());  // a new session on the same file
  PlanResult second = plan(s, earcSettings(1), &store);
  REQUIRE(second.solution.solved);
  CHECK(validateSolution(s, second.solution).valid);
  CHECK(*second.stats.db_hits + second.stats.db->db_repairs >= 1);
  CHECK(*second.stats.db->db_hit_rate > 0.0);
}

TEST_CASE("A database that cannot take what E-ARC learned costs the lesson, not the plan") {
  TempDb tmp;
  Scenario s = crossing(0, 0, 6);
  std::size_t before = 0;
  {
    exp::ExperienceStore store(tmp.file());
    before = store.size();
    store.flush();
    // A full disk, as SQLite reports it (SQLITE_FULL): no page may be
    // added to the file, and every insert of a row first writes 4 MB
    // (a temporary trigger, seen by this connection only).
    exp::Connection& c = store.connection();
    c.exec("PRAGMA max_page_count = " + std::to_string(c.pragmaInt("page_count")));
    c.exec("CREATE TEMP TRIGGER no_room BEFORE INSERT ON main.experiences BEGIN "
           "INSERT INTO history (token, at, program, operation, detail) "
           "VALUES (0, 0, 'test', 'learn', zeroblob(4000000)); END");
    PlanResult r = plan(s, earcSettings(1), &store);
    REQUIRE(r.solution.solved);
    CHECK(validateSolution(s, r.solution).valid);
    CHECK(r.stats.db->db_learn_candidates >= 1);
    CHECK(r.stats.db->db_learned == 0);
    CHECK(r.stats.db_learn_error.value_or("").find("full") != std::string::npos);
  }
  exp::ExperienceStore store(tmp.file());
  CHECK(store.size() == before);
}

TEST_CASE("failure reasons add up across queries with their numbers taken out") {
  CHECK(withoutNumbers("fewest invalid runs 4, too many to repair") == "fewest invalid runs N, too many to repair");
  CHECK(withoutNumbers("answer 95 steps, more than 1.05 x 16") == "answer N steps, more than N x N");
  CHECK(withoutNumbers("answer 95 steps, more than 3 x 16") == withoutNumbers("answer 7 steps, more than 12.5 x 2"));
  CHECK(withoutNumbers("ends. 3. .5") == "ends. N. .N");  // a point not between digits stays
  CHECK(withoutNumbers("") == "");
}

TEST_CASE("E-ARC's decoupled shadow accounts for every subproblem put to the database") {
  TempDb tmp;
  exp::ExperienceStore store(tmp.file());
  REQUIRE(plan(crossing(0, 0, 12), earcSettings(2), &store).solution.solved);  // something to retrieve
  PlannerSettings settings = earcSettings(3);
  settings.db.learn = false;
  settings.db.shadow_decoupled = true;
  PlanResult r = plan(crossing(5.0, 4.0, 12), settings, &store);
  REQUIRE(r.solution.solved);
  REQUIRE(r.stats.db->db_shadow_decoupled);
  const auto& sh = *r.stats.db->db_shadow_decoupled;
  const int queries = sh["queries"], database = sh["database_solved"], decoupled = sh["decoupled_solved"],
            both = sh["both_solved"];
  CHECK(queries == r.stats.db->db_queries);
  CHECK(queries >= 1);
  CHECK(database == *r.stats.db_hits + r.stats.db->db_repairs);
  CHECK(both <= std::min(database, decoupled));
  CHECK(sh["decoupled_seconds_where_both"].size() == static_cast<std::size_t>(both));
  CHECK(sh["database_extra_steps_where_both"].size() == static_cast<std::size_t>(both));
  int neither = 0;
  for (const auto& [why, n] : sh["database_failed_where_decoupled_failed"].items()) {
    CHECK_FALSE(why.empty());
    neither += n.get<int>();
  }
  CHECK(neither == queries - database - decoupled + both);
  // Without the flag there is no such entry.
  settings.db.shadow_decoupled = false;
  CHECK_FALSE(plan(crossing(5.0, 4.0, 12), settings, &store).stats.db->db_shadow_decoupled.has_value());
}

TEST_CASE("E-ARC reuses a mobile experience translated to where the conflict happens") {
  // The same crossing elsewhere meets the same conflicts: what was learned
  // answers them, also where the answer passes the robots outside closely
  // (seed 2: a candidate joined a step late for a rounding error in its
  // ends ran into them).
  for (std::uint64_t seed : {1, 2, 3}) {
    CAPTURE(seed);
    TempDb tmp;
    exp::ExperienceStore store(tmp.file());
    PlanResult first = plan(crossing(0, 0, 12), earcSettings(seed), &store);
    REQUIRE(first.solution.solved);
    REQUIRE(store.size() >= 1);
    Scenario moved = crossing(5.0, 4.0, 12);
    PlannerSettings settings = earcSettings(seed);
    settings.db.learn = false;
    PlanResult second = plan(moved, settings, &store);
    REQUIRE(second.solution.solved);
    CHECK(validateSolution(moved, second.solution).valid);
    CHECK(*second.stats.db_hits + second.stats.db->db_repairs >= 1);
  }
}

// Two discs swap places along x in a 10 x 10 world: a goes up and over, b
// straight (the waypoints of a stored experience, time-stamped together).
Scenario swapScenario() {
  Scenario s;
  s.name = "swap";
  s.workspace = {{0, 0}, {10, 10}};
  s.robots = {disc("a", {4, 5, 0}, {6, 5, 0}), disc("b", {6, 5, 0}, {4, 5, 0})};
  return s;
}
const std::vector<CompositeState> kSwapOverTheTop{{{4, 5, 0}, {6, 5, 0}}, {{4, 6, 0}, {6, 5, 0}},
                                                  {{6, 6, 0}, {4, 5, 0}}, {{6, 5, 0}, {4, 5, 0}}};
// The scenario with a small disc obstacle on a's way over the top.
Scenario swapBlocked() {
  Scenario s = swapScenario();
  Obstacle o;
  o.type = Obstacle::Type::Circle;
  o.center = {5, 6};
  o.radius = 0.15;
  s.obstacles.push_back(o);
  return s;
}

TEST_CASE("The database solver repairs a retrieved solution that a new obstacle cuts") {
  TempDb tmp;
  exp::ExperienceStore store(tmp.file());
  const Scenario open = swapScenario();
  const RobotModels owned(open);
  const std::vector<const RobotModel*>& models = owned.raw;
  const std::vector<CompositeState>& way = kSwapOverTheTop;
  LocalSolution stored = timeStampComposite(models, way);
  CollisionWorld open_world(open);
  CompositeChecker open_checker(open_world, models);
  for (std::size_t w = 1; w < way.size(); ++w) REQUIRE(open_checker.motionValid(way[w - 1], way[w]));
  REQUIRE(exp::learn(store, models, stored.paths, 0.1, exp::Source::Build).has_value());

  // Now a small obstacle sits on a's path over the top.
  CollisionWorld world(swapBlocked());
  RoadmapSet roadmaps(world, models, 300, 10, 1);
  std::vector<Path> plan_paths{line({{4, 5, 0}, {6, 5, 0}}), line({{6, 5, 0}, {4, 5, 0}})};
  Subproblem sub = pairSubproblem({{4, 5, 0}, {6, 5, 0}}, {{6, 5, 0}, {4, 5, 0}});
  SolverContext ctx{world, models, roadmaps, plan_paths, sub, Deadline(10), 7};
  DatabaseSolverSettings ds;
  ds.repair_time_s = 2.0;
  DatabaseSolver solver(store, ds);
  SolverOutcome out = solver.solve(ctx);
  REQUIRE(out.solution.has_value());
  CHECK(out.how == "repair");
  CHECK(out.entry >= 1);
  // The repaired local solution is valid in the new world at every step and midpoint.
  CompositeChecker checker(world, models);
  const auto& p = out.solution->paths;
  for (std::size_t t = 0; t + 1 < p[0].size(); ++t) REQUIRE(checker.motionValid(stateAt(p, t), stateAt(p, t + 1)));
  CHECK(std::vector<double>(p[0].back(), p[0].back() + 3) == sub.goals[0]);
}

TEST_CASE("invalidRuns finds the stretch an obstacle cuts and repairRuns replans only that stretch") {
  const RobotModels owned(swapScenario());
  const std::vector<const RobotModel*>& models = owned.raw;
  const std::vector<Path> paths = timeStampComposite(models, kSwapOverTheTop).paths;
  {
    CollisionWorld open_world(swapScenario());
    CHECK(invalidRuns(CompositeChecker(open_world, models), paths).empty());
  }
  CollisionWorld world(swapBlocked());
  CompositeChecker checker(world, models);
  const std::vector<StepRun> runs = invalidRuns(checker, paths);
  REQUIRE(runs.size() == 1);
  const auto [first, last] = runs.front();
  CHECK(first > 0);
  CHECK(last + 1 < paths[0].size() - 1);
  // a is over the obstacle somewhere in the run, and nowhere outside it.
  for (std::size_t t = 0; t < paths[0].size(); ++t)
    if (t < first || t > last + 1) CHECK(checker.stateValid(stateAt(paths, t)));

  const std::vector<ConfigBox> region(2, ConfigBox{{0, 0, -3.15}, {10, 10, 3.15}});
  RunRepair fix = repairRuns(world, models, paths, runs, region, 2.0, Deadline(10), 3);
  REQUIRE(fix.paths.has_value());
  CHECK(fix.why.empty());
  CHECK_FALSE(fix.out_of_time);
  const std::vector<Path>& p = *fix.paths;
  CHECK(invalidRuns(checker, p).empty());
  // Untouched up to the run's first state, and ending where it ended.
  for (std::size_t t = 0; t <= first; ++t) CHECK(stateAt(p, t) == stateAt(paths, t));
  CHECK(stateAt(p, p[0].size() - 1) == stateAt(paths, paths[0].size() - 1));
  CHECK(p[0].size() == p[1].size());

  // No time left: nothing replanned, and it says why.
  RunRepair late = repairRuns(world, models, paths, runs, region, 2.0, Deadline(0), 3);
  CHECK_FALSE(late.paths.has_value());
  CHECK(late.out_of_time);
  CHECK(late.why == "no time left to repair");
}

// The library's error names no program's option: the caller's mistake.
TEST_CASE("E-ARC without a database is refused with a clear error") {
  CHECK_THROWS_WITH_AS(plan(crossing(0, 0, 6), earcSettings(1), nullptr),
                       "method earc needs an experience store (none was given)", std::invalid_argument);
}

// Two discs in a 10 x 10 world drive side by side in +x from x = 4 to 6,
// a at y = 4 and b at y = 6.
Scenario sideBySide() {
  Scenario s;
  s.name = "parallel";
  s.workspace = {{0, 0}, {10, 10}};
  s.robots = {disc("a", {4, 4, 0}, {6, 4, 0}), disc("b", {4, 6, 0}, {6, 6, 0})};
  return s;
}

TEST_CASE("A retrieved mobile solution is turned to the start headings and shortcut before use") {
  TempDb tmp;
  exp::ExperienceStore store(tmp.file());
  // Stored: two discs drive side by side in +x, facing along x, robot a
  // with a pointless loop up and back that a shortcut removes.
  const Scenario open = sideBySide();
  const RobotModels owned(open);
  const std::vector<const RobotModel*>& models = owned.raw;
  std::vector<CompositeState> way{{{4, 4, 0}, {4, 6, 0}}, {{5, 4, 0}, {5, 6, 0}}, {{5, 5, 0}, {5, 6, 0}},
                                  {{5, 4, 0}, {5, 6, 0}}, {{6, 4, 0}, {6, 6, 0}}};
  LocalSolution stored = timeStampComposite(models, way);
  const std::size_t stored_steps = stored.length();
  REQUIRE(exp::learn(store, models, stored.paths, 0.1, exp::Source::Build).has_value());

  // The same motion asked for with both discs facing +y (pi/2) throughout:
  // joined without turning, the robots would first spin a quarter turn on
  // the spot (pi/2 / 0.05 = 32 steps) and back at the end.
  CollisionWorld world(open);
  RoadmapSet roadmaps(world, models, 300, 10, 1);
  const double up = 1.5707963267948966;
  Subproblem sub = pairSubproblem({{4, 4, up}, {4, 6, up}}, {{6, 4, up}, {6, 6, up}});
  std::vector<Path> plan_paths{line({sub.starts[0], sub.goals[0]}), line({sub.starts[1], sub.goals[1]})};
  SolverContext ctx{world, models, roadmaps, plan_paths, sub, Deadline(10), 7};
  DatabaseSolver solver(store, DatabaseSolverSettings{});
  SolverOutcome out = solver.solve(ctx);
  REQUIRE(out.solution.has_value());
  CHECK(out.how == "database");
  const auto& p = out.solution->paths;
  for (int r = 0; r < 2; ++r) {
    CHECK(p[r].at(0)[2] == doctest::Approx(up));
    CHECK(p[r].back()[2] == doctest::Approx(up));
    for (std::size_t t = 0; t < p[r].size(); ++t) REQUIRE(p[r].at(t)[2] == doctest::Approx(up));  // never turned
  }
  // The loop is gone: 2 units at 0.05 per step are 40 steps.
  CHECK(out.solution->length() < stored_steps);
  CHECK(out.solution->length() <= 41);
}

TEST_CASE("A stored candidate no step count follows is passed over, and the query goes on with the others") {
  TempDb tmp;
  exp::ExperienceStore store(tmp.file());
  // Stored at 0.05 per step: two discs side by side in +x, and the same
  // with one state of a's 9.5e5 units away in x and y, within what the
  // store holds (kMaxStoredPosition), as a made-up row could be.
  const Scenario open = sideBySide();
  const RobotModels coarse(open);
  const std::vector<Path> stored =
      timeStampComposite(coarse.raw, {{{4, 4, 0}, {4, 6, 0}}, {{6, 4, 0}, {6, 6, 0}}}).paths;
  std::vector<Path> far = stored;
  double* q = far[0].mutableAt(far[0].size() / 2);
  q[0] = q[1] = 5 + 9.5e5;
  const auto far_id = exp::learn(store, coarse.raw, far, 0.1, exp::Source::Build, -1);
  REQUIRE(far_id.has_value());

  // Asked at 5e-4 per step, that state is 2.7e9 steps away: more than an
  // int counts.
  Scenario fine = open;
  fine.resolution.translation = 5e-4;
  const RobotModels models(fine);
  CollisionWorld world(fine);
  RoadmapSet roadmaps(world, models.raw, 300, 10, 1);
  Subproblem sub = pairSubproblem({{4, 4, 0}, {4, 6, 0}}, {{6, 4, 0}, {6, 6, 0}});
  std::vector<Path> plan_paths{line({sub.starts[0], sub.goals[0]}), line({sub.starts[1], sub.goals[1]})};
  SolverContext ctx{world, models.raw, roadmaps, plan_paths, sub, Deadline(30), 7};
  {
    DatabaseSolver alone(store, DatabaseSolverSettings{});
    SolverOutcome none = alone.solve(ctx);
    CHECK_FALSE(none.solution.has_value());
    CHECK(none.detail == "1 candidates: 0 ends blocked, 0 invalid, 0 crowded, 1 unusable; none to repair");
  }
  // With a sound row beside it, the sound one answers.
  const auto sound_id = exp::learn(store, coarse.raw, stored, 0.1, exp::Source::Build, -1);
  REQUIRE(sound_id.has_value());
  DatabaseSolver solver(store, DatabaseSolverSettings{});
  SolverOutcome out = solver.solve(ctx);
  REQUIRE(out.solution.has_value());
  CHECK(out.how == "database");
  CHECK(out.entry == *sound_id);
  CompositeChecker checker(world, models.raw);
  const auto& p = out.solution->paths;
  for (std::size_t t = 0; t + 1 < p[0].size(); ++t) REQUIRE(checker.motionValid(stateAt(p, t), stateAt(p, t + 1)));
  PlanStats stats;
  solver.finish(stats);
  CHECK(stats.db->db_skipped_unusable == 1);
  CHECK(stats.db_hits == 1);
  // Its use counted as a failure, as an invalid candidate's is.
  auto row = store.get(*far_id);
  REQUIRE(row.has_value());
  CHECK(row->retrieved == 2);
  CHECK(row->succeeded == 0);
}

namespace {

// a and b drive side by side in +x from x = 4 to 6 (a at y = 4, b at
// y = 6); c, not in the subproblem, is parked on a's way (5, 4) for the
// whole time.
struct ParkedRobot {
  Scenario s = [] {
    Scenario sc;
    sc.name = "parked";
    sc.workspace = {{0, 0}, {10, 10}};
    sc.robots = {disc("a", {4, 4, 0}, {6, 4, 0}), disc("b", {4, 6, 0}, {6, 6, 0}), disc("c", {5, 4, 0}, {5, 4, 0})};
    return sc;
  }();
  RobotModels owned{s};
  const std::vector<const RobotModel*>& all = owned.raw;
  std::vector<const RobotModel*> pair{all[0], all[1]};
  CollisionWorld world{s};
  RoadmapSet roadmaps{world, all, 300, 10, 1};
  Subproblem sub = pairSubproblem({{4, 4, 0}, {4, 6, 0}}, {{6, 4, 0}, {6, 6, 0}});
  std::vector<Path> plan_paths{line({sub.starts[0], sub.goals[0]}), line({sub.starts[1], sub.goals[1]}),
                               line({{5, 4, 0}, {5, 4, 0}})};

  // Stores a's and b's motion through the given composite waypoints.
  void store(exp::ExperienceStore& db, const std::vector<CompositeState>& way) const {
    LocalSolution st = timeStampComposite(pair, way);
    REQUIRE(exp::learn(db, pair, st.paths, 0.1, exp::Source::Build).has_value());
  }

  // The subproblem put to `solver` with c parked on a's way, then with c
  // parked out of the way.
  std::pair<SolverOutcome, SolverOutcome> solveParkedThenAway(DatabaseSolver& solver) {
    SolverContext ctx{world, all, roadmaps, plan_paths, sub, Deadline(10), 7};
    SolverOutcome parked = solver.solve(ctx);
    std::vector<Path> away = plan_paths;
    away[2] = line({{5, 8.5, 0}, {5, 8.5, 0}});
    SolverContext clear{world, all, roadmaps, away, sub, Deadline(10), 7};
    return {std::move(parked), solver.solve(clear)};
  }
};

}  // namespace

TEST_CASE("The database solver refuses a stored solution that runs into a robot outside the subproblem") {
  TempDb tmp;
  exp::ExperienceStore store(tmp.file());
  ParkedRobot f;
  f.store(store, {{{4, 4, 0}, {4, 6, 0}}, {{6, 4, 0}, {6, 6, 0}}});
  DatabaseSolver solver(store, DatabaseSolverSettings{});
  auto [out, used] = f.solveParkedThenAway(solver);
  CHECK_FALSE(out.solution.has_value());
  // The trace says what became of the candidates.
  CHECK(out.detail == "1 candidates: 0 ends blocked, 0 invalid, 1 crowded; none to repair");
  // With c parked out of the way the same entry is used.
  REQUIRE(used.solution.has_value());
  CHECK(used.how == "database");
  PlanStats stats;
  solver.finish(stats);
  CHECK(stats.db->db_refused_crowded == 1);
  CHECK(stats.db_hits == 1);

  // Told to ignore the robots outside (ARC's retries beyond its last
  // level), the solver uses the entry and leaves c to a later conflict.
  SolverContext ignoring{f.world, f.all, f.roadmaps, f.plan_paths, f.sub, Deadline(10), 7};
  ignoring.ignore_others = true;
  SolverOutcome through = solver.solve(ignoring);
  REQUIRE(through.solution.has_value());
  CHECK(through.how == "database");
}

TEST_CASE("A stored solution that runs into a robot outside before its invalid stretch is not repaired") {
  TempDb tmp;
  exp::ExperienceStore store(tmp.file());
  ParkedRobot f;
  // a drives straight through c's place; b dips towards a's line and
  // touches a half-way: one invalid run, after a has reached c.
  f.store(store, {{{4, 4, 0}, {4, 6, 0}}, {{5, 4, 0}, {5, 4.5, 0}}, {{6, 4, 0}, {6, 6, 0}}});
  DatabaseSolverSettings ds;
  ds.repair_time_s = 2.0;
  DatabaseSolver solver(store, ds);
  auto [out, used] = f.solveParkedThenAway(solver);
  CHECK_FALSE(out.solution.has_value());
  CHECK(out.detail == "1 candidates: 0 ends blocked, 1 invalid, 0 crowded; crowded before repair");
  // With c parked out of the way the same entry is repaired and used.
  REQUIRE(used.solution.has_value());
  CHECK(used.how == "repair");
}

TEST_CASE("After three stored solutions run into robots outside the subproblem, the database hands over") {
  ParkedRobot f;
  // `straight` entries where a drives straight through c (b a little
  // higher or lower each time, so that no entry is a near duplicate of
  // another), then one where a drives round c below it: the longest, so
  // the last candidate tried.
  auto run = [&](int straight) {
    TempDb tmp;
    exp::ExperienceStore store(tmp.file());
    const double b_rows[] = {6.0, 6.3, 5.7};
    for (int i = 0; i < straight; ++i) {
      const double y = b_rows[i];
      f.store(store, {{{4, 4, 0}, {4, y, 0}}, {{6, 4, 0}, {6, y, 0}}});
    }
    f.store(store,
            {{{4, 4, 0}, {4, 6.15, 0}}, {{4, 2.5, 0}, {4, 6.15, 0}}, {{6, 2.5, 0}, {6, 6.15, 0}}, {{6, 4, 0}, {6, 6.15, 0}}});
    DatabaseSolver solver(store, DatabaseSolverSettings{});
    SolverContext ctx{f.world, f.all, f.roadmaps, f.plan_paths, f.sub, Deadline(10), 7};
    return solver.solve(ctx);
  };

  // Two crowded candidates: the query goes on to the way round.
  SolverOutcome two = run(2);
  REQUIRE(two.solution.has_value());
  CHECK(two.how == "database");
  bool went_round = false;
  for (std::size_t t = 0; t < two.solution->paths[0].size(); ++t) went_round |= two.solution->paths[0].at(t)[1] < 3.0;
  CHECK(went_round);

  // Three: the region is taken to be busy, and neither the way round nor
  // a repair is tried.
  SolverOutcome three = run(3);
  CHECK_FALSE(three.solution.has_value());
  CHECK(three.detail == "4 candidates: 0 ends blocked, 0 invalid, 3 crowded; region busy with other robots");
}
