// E-ARC's database solver on arms: answers for two arms retimed arm by arm,
// and the next entries read when the nearest are blocked at their ends.
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "earc/collision/collision_world.hpp"
#include "earc/experience/retrieval.hpp"
#include "earc/experience/store.hpp"
#include "earc/io/input_error.hpp"
#include "earc/planning/composite.hpp"
#include "earc/planning/coupled_solver.hpp"
#include "earc/methods/database_solver.hpp"
#include "earc/planning/planner.hpp"
#include "earc/validate/validator.hpp"
#include "support.hpp"

using earc::test::line;
using earc::test::TempDb;

using namespace earc;
namespace fs = std::filesystem;

namespace {

// Two arms face each other across 4 units with 2.5 of reach each: a at the
// bottom swings from right to left through b's straight-down pose. `way`:
// b folds aside, then a swings, then b comes back, each waiting for the
// other.
struct FacingArms {
  static RobotSpec armSpec(const std::string& name, double y, double angle) {
    RobotSpec s = RobotSpec::arm(name, {3, y}, angle, std::vector<double>(5, 0.5), 0.05);
    s.joint_limits.assign(5, {-2.6, 2.6});
    return s;
  }
  static constexpr double kHalfPi = 1.5707963267948966;
  Scenario sc = [] {
    Scenario s;
    s.name = "facing";
    s.workspace = {{0, 0}, {6, 10}};
    s.robots = {armSpec("a", 3, kHalfPi), armSpec("b", 7, -kHalfPi)};
    s.robots[0].start = {-1.2, 0, 0, 0, 0};
    s.robots[0].goal = {1.2, 0, 0, 0, 0};
    s.robots[1].start = s.robots[1].goal = {0, 0, 0, 0, 0};
    return s;
  }();
  RobotModels owned{sc};
  const std::vector<const RobotModel*>& models = owned.raw;
  CollisionWorld world{sc};
  CompositeChecker checker{world, models};
  std::vector<double> folded{1.2, 0, 0, 0, 0};
  std::vector<CompositeState> way{{sc.robots[0].start, sc.robots[1].start},
                                  {sc.robots[0].start, folded},
                                  {sc.robots[0].goal, folded},
                                  {sc.robots[0].goal, sc.robots[1].goal}};
  RoadmapSet roadmaps{world, models, 200, 10, 1};

  // Stores `way`'s motion; returns its id.
  std::int64_t storeWay(exp::ExperienceStore& store) const {
    auto id = exp::learn(store, models, timeStampComposite(models, way).paths, 0.1, exp::Source::Build);
    REQUIRE(id.has_value());
    return *id;
  }

  // The subproblem from `starts` to `goals` over the whole workspace.
  Subproblem subproblem(const CompositeState& starts, const CompositeState& goals) const {
    Subproblem sub;
    sub.robots = {0, 1};
    sub.starts = starts;
    sub.goals = goals;
    for (const auto* m : models) {
      ConfigBox box;
      m->samplingBounds(world.workspace(), box.lo, box.hi);
      sub.region.push_back(box);
    }
    sub.workspace_region = world.workspace();
    sub.t_start = 0;
    sub.t_end = 1;
    return sub;
  }

  // Asks the database solver for sub (robots 0 and 1 outside it: none).
  SolverOutcome ask(exp::ExperienceStore& store, const Subproblem& sub, const DatabaseSolverSettings& ds) {
    std::vector<Path> plan_paths{line({sub.starts[0], sub.goals[0]}), line({sub.starts[1], sub.goals[1]})};
    DatabaseSolver solver(store, ds);
    SolverContext ctx{world, models, roadmaps, plan_paths, sub, Deadline(10), 7};
    return solver.solve(ctx);
  }

  // Valid at every step and midpoint, one resolution step at a time, from
  // sub's starts to its goals.
  void checkAnswer(const LocalSolution& sol, const Subproblem& sub) const {
    const auto& p = sol.paths;
    REQUIRE(p[0].size() == p[1].size());
    for (std::size_t t = 0; t + 1 < p[0].size(); ++t) {
      for (std::size_t r = 0; r < 2; ++r) CHECK(models[r]->stepsBetween(p[r].at(t), p[r].at(t + 1)) <= 1);
      CHECK(checker.motionValid(stateAt(p, t), stateAt(p, t + 1)));
    }
    CHECK(stateAt(p, 0) == sub.starts);
    CHECK(stateAt(p, p[0].size() - 1) == sub.goals);
  }
};

}  // namespace

TEST_CASE("An answer for two arms is retimed: each arm moves when the other lets it, and sooner") {
  // Composite shortcuts move both arms together; retiming lets a set off
  // while b is still folding and b come back once a has passed.
  FacingArms f;
  for (std::size_t w = 1; w < f.way.size(); ++w) REQUIRE(f.checker.motionValid(f.way[w - 1], f.way[w]));
  REQUIRE_FALSE(f.checker.motionValid(f.way.front(), f.way.back()));  // b must get out of the way

  TempDb tmp;
  exp::ExperienceStore store(tmp.file());
  f.storeWay(store);
  const Subproblem sub = f.subproblem(f.way.front(), f.way.back());
  // Steps until each arm's last move, summed over the arms.
  auto costs = [](const LocalSolution& sol) {
    std::size_t sum = 0;
    for (const auto& p : sol.paths) {
      std::size_t last = p.size() - 1;
      while (last > 0 && std::equal(p.at(last), p.at(last) + p.dim(), p.at(last - 1))) --last;
      sum += last;
    }
    return sum;
  };
  auto answer = [&](int retime) {
    DatabaseSolverSettings ds;
    ds.retime_iterations = retime;
    SolverOutcome out = f.ask(store, sub, ds);
    REQUIRE(out.solution.has_value());
    CHECK(out.how == "database");
    return *out.solution;
  };
  const LocalSolution plain = answer(0), retimed = answer(100);
  CHECK(costs(retimed) < costs(plain));
  CHECK(retimed.length() < plain.length());
  f.checkAnswer(retimed, sub);
}

TEST_CASE("When the k nearest arm entries are all blocked at their ends, the database solver reads the next ones") {
  // The key holds the first kArmKeyJoints joints. Eleven stored entries lie
  // nearer in key space than `way` (0.04 from the query along one key axis
  // each, 0.057 apart, so none is a near duplicate of another), but with
  // the outer joints set so that the query's start or goal cannot be
  // joined to them. `way` itself is 0.1 away.
  FacingArms f;
  CompositeState starts = f.way.front(), goals = f.way.back();
  starts[0][0] = -1.3;
  REQUIRE(f.checker.stateValid(starts));
  const Subproblem sub = f.subproblem(starts, goals);

  TempDb tmp;
  exp::ExperienceStore store(tmp.file());
  const std::int64_t way_id = f.storeWay(store);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> joint(-2.6, 2.6);
  const int key_joints = exp::kArmKeyJoints;
  for (int axis = 0; axis < 11; ++axis) {
    // Key axes, robot by robot: start joints, then goal joints.
    const int robot = axis / (2 * key_joints), at_goal = (axis / key_joints) % 2, j = axis % key_joints;
    CompositeState s = starts, g = goals;
    CompositeState& moved = at_goal ? g : s;
    moved[static_cast<std::size_t>(robot)][static_cast<std::size_t>(j)] += 0.04;
    const CompositeState& from = at_goal ? goals : starts;
    int tries = 0;
    do {
      REQUIRE(++tries < 5000);
      for (auto& q : moved)
        for (std::size_t k = static_cast<std::size_t>(key_joints); k < q.size(); ++k) q[k] = joint(rng);
    } while (at_goal ? f.checker.motionValid(moved, from) : f.checker.motionValid(from, moved));
    REQUIRE(exp::learn(store, f.models, timeStampComposite(f.models, {s, g}).paths, 0.1, exp::Source::Build)
                .has_value());
  }

  DatabaseSolverSettings narrow;
  narrow.widen_k = narrow.k;
  SolverOutcome none = f.ask(store, sub, narrow);
  CHECK_FALSE(none.solution.has_value());
  CHECK(none.detail == "10 candidates: 10 ends blocked, 0 invalid, 0 crowded; none to repair");

  SolverOutcome out = f.ask(store, sub, DatabaseSolverSettings{});
  REQUIRE(out.solution.has_value());
  CHECK(out.how == "database");
  CHECK(out.entry == way_id);
  f.checkAnswer(*out.solution, sub);
}
