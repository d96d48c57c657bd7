// E-ARC's first solver: look the subproblem up in the experience store
// (the paper's "DatabasePlanning", Algorithm 2). Retrieve the k closest
// solutions of the subproblem's class (translated to the conflict for
// mobile robots, roles swapped for a negative base-transform match of two
// arms), keep those whose ends connect to the local start and goal without
// collision, use the first that is valid against the world, else repair
// the one with the fewest invalid segments when they are few, else hand
// over to planning from scratch. Subproblems the later solvers solve are
// learned (inserted when planning ends).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "earc/experience/store.hpp"
#include "earc/planning/composite.hpp"
#include "earc/planning/planner.hpp"
#include "earc/planning/solver.hpp"

namespace earc {

struct DatabaseSolverSettings {
  std::size_t k = 10;             // candidates retrieved
  std::size_t widen_k = 40;       // arms: up to this many when all k are blocked at their ends
  int max_invalid_segments = 3;   // repair only up to this many invalid runs
  double repair_time_s = 0.1;     // composite replanning budget per run
  int retime_iterations = 100;    // retimeShortcut attempts on an answer for arms
  // Refuse an answer longer than this many times the steps its slowest
  // robot needs to go straight from start to goal (0: take any length).
  double max_stretch = 0.0;
  bool learn = true;              // insert subproblems solved from scratch, count uses
  bool shadow_decoupled = false;  // see DatabaseSettings::shadow_decoupled
};

// What the database answered in an E-ARC plan (its subproblems_by_solver):
// subproblems solved in all, and by a retrieved or repaired answer. The
// one count of db_hit_rate, earc-plan's summary and serve's counters.
struct DatabaseAnswers {
  std::int64_t solved = 0, retrieved = 0, repaired = 0;
  std::int64_t answered() const { return retrieved + repaired; }
  // Answered over solved; 0 when nothing was solved.
  double hitRate() const { return solved > 0 ? static_cast<double>(answered()) / static_cast<double>(solved) : 0.0; }
  DatabaseAnswers& operator+=(const DatabaseAnswers& o) {
    solved += o.solved;
    retrieved += o.retrieved;
    repaired += o.repaired;
    return *this;
  }
};
DatabaseAnswers databaseAnswers(const PlanStats& stats);

// A failure reason with each number (3, 16, 1.05) replaced by N, so that
// reasons of different queries add up: "answer N steps, more than N x N".
std::string withoutNumbers(std::string_view text);

class DatabaseSolver : public SubproblemSolver {
 public:
  DatabaseSolver(exp::ExperienceStore& store, DatabaseSolverSettings s)
      : store_(store), settings_(s), retrieval_at_start_(store.retrievalStats()) {}
  const char* name() const override { return "database"; }
  SolverOutcome solve(SolverContext& ctx) override;
  void accepted(const SolverContext& ctx, const LocalSolution& sol, const SolverOutcome& by) override;
  void finish(PlanStats& stats) override;

  // The paper's database holds 2-, 3- and 4-robot subproblems.
  static constexpr std::size_t kMaxRobots = 4;

 private:
  // One lookup (database_query.cpp): an answer, or why there is none.
  struct QueryState;
  SolverOutcome query(SolverContext& ctx);
  // The store's usage counters for row id, when learning.
  void recordUse(std::int64_t id, bool success);
  // What the decoupled solver makes of the subproblem the database was
  // just asked (`db`), for the db_shadow_decoupled stats.
  void shadow(SolverContext& ctx, const SolverOutcome& db);

  // start -> candidate's first state, the candidate, last state -> goal,
  // shortcut and, for arms, retimed (when asked), then held at the goals
  // through the window.
  LocalSolution connect(const CompositeChecker& checker, const SolverContext& ctx,
                        const std::vector<const RobotModel*>& robots, const std::vector<Path>& middle,
                        bool shortcut) const;

  struct Pending {
    std::vector<const RobotModel*> robots;
    std::vector<Path> paths;
    double seconds = 0.0;
  };
  exp::ExperienceStore& store_;
  DatabaseSolverSettings settings_;
  std::vector<Pending> pending_;
  int queries_ = 0;
  int hits_ = 0;
  int repairs_ = 0;
  int crowded_ = 0;  // valid candidates refused for running into other robots
  int too_long_ = 0;  // answers refused for max_stretch
  double retrieval_s_ = 0.0;  // wall time in retrieveCandidates
  exp::ExperienceStore::RetrievalStats retrieval_at_start_;
  int unusable_ = 0;  // candidates passed over: no step count joins or follows them (NoStepCountError)
  // Subproblems solved from scratch that no class can hold (3 or more arms,
  // 5 or more robots, arms of unequal joints or too many): never learned.
  int unstorable_ = 0;
  // What became of the last query's candidates (its trace detail), and why
  // it failed; why is empty when the subproblem's size has no class.
  struct Tally {
    std::size_t candidates = 0;
    int ends_blocked = 0, invalid = 0, crowded = 0, unusable = 0;
    std::size_t too_long = 0;  // the steps of an answer refused for max_stretch
    std::string why;
    // why with its numbers taken out, so that reasons of queries add up.
    std::string general() const;
  } tally_;
  struct Shadow {
    int queries = 0, database = 0, decoupled = 0, both = 0;
    std::vector<double> decoupled_s_both;  // decoupled's time where both solved
    std::vector<long> extra_steps_both;    // database's length minus decoupled's
    std::map<std::string, int> database_failed_where_decoupled_failed;  // by reason
  } shadow_;
};

// E-ARC: ARC with the database solver over `store` first in its hierarchy.
// Throws std::invalid_argument when store is null.
PlanResult planEarc(const Scenario& scenario, const PlannerSettings& settings, exp::ExperienceStore* store,
                    const PlanContext& context = {});

}  // namespace earc
