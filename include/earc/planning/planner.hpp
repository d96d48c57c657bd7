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

// The individual roadmaps (ARC, E-ARC, prioritized, refinement).
struct RoadmapSettings {
  int samples = 0;  // 0: chosen from the workspace and robot size
  int neighbors = 10;
};

// ARC's and E-ARC's subproblems.
struct ArcSettings {
  int initial_window = 8;      // steps before and after the conflict
  double region_margin = 1.0;  // plane units (mobile) around the local query
  double joint_margin = 0.6;   // radians (arms)
  int max_expansions = 12;
  // Merging stops at this many robots (at least 2), except for a conflict
  // that keeps coming back (ConflictRecurrence, arc.hpp).
  int max_merged_robots = 5;
  // Hand a jam to the crowd solver (lacam.hpp) when the local solvers fail
  // on it; false: never (the methods as published).
  bool crowd_fallback = true;
  // Retime each mobile robot of a local answer inside its window before the
  // splice (retimeLocalSolution, arc.hpp); stats "window_retimed".
  bool retime_windows = false;
  // Time-stamp each coupled answer robot by robot, not in lockstep
  // (restampLocalSolution, arc.hpp); stats "coupled_restamped".
  bool restamp_coupled = false;
  // Local solvers hold robots parked at their goals first (DecoupledSettings::
  // parked_detour, CoupledSolverSettings::parked_held).
  bool hold_parked = false;
  // The valid plan's mobile robots compacted (compactRobots, compact.hpp):
  // passes (0: none) and states searched per route position.
  int compact_passes = 1;
  int compact_states = 8;
  // Then the routes of this many of them, those furthest behind their
  // straight-line arrival (a quarter late or more), shortcut with so many
  // tries each (shortcutRobots, compact.hpp).
  int compact_shortcut_robots = 32;
  int compact_shortcut_tries = 8;
};

// The experience databases: E-ARC's store and Lightning's file.
struct DatabaseSettings {
  int k = 10;                    // candidates retrieved per subproblem (E-ARC)
  int max_invalid_segments = 3;  // repair at most this many segments (E-ARC)
  double max_stretch = 0.0;      // refuse longer answers (DatabaseSolverSettings::max_stretch); 0: off
  bool learn = true;             // insert subproblems solved from scratch (E-ARC), the solution (Lightning)
  // E-ARC diagnostic: also run the decoupled solver on every subproblem put
  // to the database (stats db_shadow_decoupled).
  bool shadow_decoupled = false;
  // Lightning's file (OMPL's format); empty: an empty database, none
  // written. A missing file is created when learn is set.
  std::string lightning_file;
};

// What every method's plan goes through once it is valid.
struct PostPlanSettings {
  // Leave out the waits each robot does not need (compactPlan, compact.hpp);
  // stats "compact".
  bool compact = false;
  // Seconds spent improving the first valid plan (refinePlan, refine.hpp),
  // within time_limit_s; 0: off. Stats "refine".
  double refine_s = 0.0;
};

// How to plan: the settings every method reads, then each group's own.
struct PlannerSettings {
  Method method = Method::Arc;
  double time_limit_s = 60.0;
  std::uint64_t seed = 1;
  bool trace = false;  // record a trace of conflicts and subproblems
  // ARC's and E-ARC's solver attempts count their budgets in work done, not
  // seconds (Deadline::withWorkBudgets): the same seed, the same plan on
  // any machine of the same build, unless time_limit_s stops it.
  bool work_budgets = false;
  // Refuse as too large a scenario whose straight start-to-goal motions
  // alone take more time-stamped scalars (8 bytes each).
  std::int64_t max_path_scalars = std::int64_t{1} << 24;  // 128 MiB
  RoadmapSettings roadmap;
  ArcSettings arc;
  DatabaseSettings db;
  PostPlanSettings post;
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
