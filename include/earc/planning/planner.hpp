// What every planning method takes and returns: the method's name, its
// settings, and a result carrying the solution, why it failed if it did,
// its statistics and (on request) a trace. plan() is in methods/plan.hpp.
#pragma once

#include <atomic>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "earc/planning/plan_stats.hpp"
#include "earc/scene/scenario.hpp"
#include "earc/scene/solution.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

namespace exp { class ExperienceStore; }
class RoadmapCache;

enum class Method { Arc, Earc, Prioritized, Coupled, Lightning, Lacam };
const char* methodName(Method m);
Method methodFromName(const std::string& name);  // throws std::invalid_argument
// The refusal of work budgets (PlannerSettings::work_budgets) for Lightning,
// to follow the option or request field that asked for them.
inline constexpr const char* kWorkBudgetsNotForLightning =
    "is not for method lightning (it races two planners on two threads; its plans follow the machine's timing)";

// How far a running plan has got, written by the planner (ARC and E-ARC) and
// read by another thread that draws a progress line. Thread-safe.
struct PlanProgress {
  std::atomic<int> individual_paths{0};   // robots with an individual path so far
  std::atomic<int> conflicts{0};          // conflicts found; the last is being resolved
  std::atomic<int> conflict_step{0};      // its time step (conflicts are resolved in time order)
  std::atomic<int> steps{0};              // of the longest path then
  std::atomic<int> subproblem_robots{0};  // robots in the subproblem being solved
  std::atomic<int> expansions{0};         // its window expansion level
};

struct PlannerSettings {
  Method method = Method::Arc;
  double time_limit_s = 60.0;
  std::uint64_t seed = 1;
  bool trace = false;                 // record a trace of conflicts and subproblems
  // ARC's and E-ARC's solver attempts count their budgets in work done, not
  // seconds (Deadline::withWorkBudgets): the same seed, the same plan on
  // any machine of the same build, unless time_limit_s stops it.
  bool work_budgets = false;
  // Individual roadmaps.
  int roadmap_samples = 0;            // 0: chosen from the workspace and robot size
  int roadmap_neighbors = 10;
  // ARC's subproblems.
  int initial_window = 8;             // steps before and after the conflict
  double region_margin = 1.0;         // plane units (mobile) around the local query
  double joint_margin = 0.6;          // radians (arms)
  int max_expansions = 12;
  // Merging stops at this many robots (at least 2), except for a conflict
  // that keeps coming back (ConflictRecurrence, arc.hpp).
  int max_merged_robots = 5;
  // E-ARC's database solver.
  int db_k = 10;                      // candidates retrieved per subproblem
  int db_max_invalid_segments = 3;    // repair at most this many segments
  double db_max_stretch = 0.0;        // refuse longer answers (DatabaseSolverSettings::max_stretch); 0: off
  bool db_learn = true;               // insert subproblems solved from scratch (E-ARC), the solution (Lightning)
  // Diagnostic: also run the decoupled solver on every subproblem put to the
  // database and report what each solved (stats db_shadow_decoupled).
  bool db_shadow_decoupled = false;
  // After planning, leave out the waits each robot does not need
  // (compactPlan, compact.hpp); stats "compact".
  bool compact = false;
  // Seconds spent after the first valid plan improving it (refinePlan,
  // refine.hpp), within time_limit_s; 0: off. Stats "refine".
  double refine_s = 0.0;
  // Crowds: ARC and E-ARC hand a jam to the configuration-based crowd
  // solver (lacam.hpp) when their local solvers fail on it; false: never.
  bool crowd_fallback = true;
  // Lightning's database file (OMPL's format): empty starts from an empty
  // database and writes none; a missing file is created when db_learn is set.
  std::string lightning_db;
  // A scenario whose straight start-to-goal motions alone would take more
  // time-stamped scalars than this (8 bytes each) is refused as too large.
  std::int64_t max_path_scalars = std::int64_t{1} << 24;  // 128 MiB
};

// What a plan runs with besides its settings, owned by the caller and kept
// alive through the plan; every member may be null. Not part of the result.
struct PlanContext {
  // Roadmaps kept from earlier plans, used and filled by ARC, E-ARC,
  // prioritized and refinement (the same plan either way). Not thread-safe.
  RoadmapCache* roadmap_cache = nullptr;
  PlanProgress* progress = nullptr;  // filled in as planning goes (ARC, E-ARC)
  // Once set (from any thread or a signal handler), planning stops soon
  // and the plan ends unsolved with FailureCause::TimeLimit.
  const StopFlag* stop = nullptr;
};

enum class FailureCause { TimeLimit, InvalidInput, NoIndividualPath, SubproblemUnsolved, InvalidResult, TooLarge };
const char* failureCauseName(FailureCause c);

struct PlanResult {
  Solution solution;                    // solved only when it validated
  std::set<FailureCause> failures;      // empty when solved
  PlanStats stats;
  nlohmann::json trace = nullptr;       // earc.trace.v1 when settings.trace
};

// The scenario, unless it has no robot: then throws InputError naming
// `source` and $.robots.
Scenario requireRobots(Scenario scenario, const std::string& source);

}  // namespace earc
