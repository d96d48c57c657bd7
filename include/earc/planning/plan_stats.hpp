// A plan's statistics, typed, and their JSON form (a solution file's
// "stats"): what every method reports and each method's own figures.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace earc {

// A jam ARC handed to the crowd solver: its robots, whether it was solved.
struct CrowdHandover {
  std::int64_t robots = 0;
  bool solved = false;
  double s = 0.0;
};

// ARC's and E-ARC's run (top-level keys: conflicts, subproblems, ...).
struct ArcStats {
  double individual_paths_s = 0.0;
  std::int64_t conflicts = 0, subproblems = 0, window_expansions = 0;
  std::map<std::string, std::int64_t> subproblems_by_solver;  // "database", "repair", "decoupled", ...
  std::map<std::string, std::int64_t> subproblems_by_robots;  // by group size, "2", "3", ...
  std::map<std::string, double> solver_time_s;
  std::string solver_budgets;  // "work" or "seconds"
  std::int64_t robots_merged = 0, merge_cap_raised = 0;
  std::vector<CrowdHandover> crowd_handovers;
  double crowd_s = 0.0;
  std::int64_t roadmap_edge_checks = 0, roadmaps_built = 0, roadmap_vertices = 0;
  double roadmap_build_s = 0.0;
  // Steps a group's robots no longer wait at their window goals (ARC's splice).
  std::optional<std::int64_t> waits_left_out;
  // Steps of arrival its robots saved, retimed inside their windows.
  std::optional<std::int64_t> window_retimed;
  // Coupled answers time-stamped robot by robot (of them, around the robots
  // outside the group too), left in lockstep, and the arrival steps saved.
  std::optional<std::int64_t> coupled_restamped, coupled_restamped_around, coupled_lockstep, restamped_steps;
  // The valid plan compacted (ArcSettings::compact_passes): steps saved, seconds.
  std::optional<std::int64_t> compacted_steps;
  std::optional<double> compacted_s;
};

// E-ARC's database solver (top-level keys db_*; db_hits is PlanStats's).
struct DatabaseStats {
  std::int64_t db_queries = 0, db_repairs = 0, db_refused_crowded = 0, db_refused_too_long = 0;
  std::int64_t db_skipped_unusable = 0, db_learned = 0, db_learn_candidates = 0, db_learn_unstorable = 0;
  std::vector<std::int64_t> db_learned_ids;
  double db_learn_time_s = 0.0;
  // Time in the store's nearest-row queries, the store's row cache while the plan ran,
  // and of its misses those decoded from a PostgreSQL store's background copy.
  std::optional<double> db_retrieval_time_s;
  std::optional<std::int64_t> db_row_cache_hits, db_row_cache_misses, db_warm_copy_hits;
  std::optional<double> db_hit_rate;                 // retrieved or repaired over solved
  std::optional<nlohmann::json> db_shadow_decoupled;  // with DatabaseSettings::shadow_decoupled
};

// Lightning's database (top-level keys lightning_*).
struct LightningStats {
  std::int64_t lightning_db_entries = 0;
  std::optional<std::int64_t> lightning_db_added, lightning_repaired_runs;
  std::optional<std::string> lightning_source;  // "recall" or "scratch"
};

// A refinement's cost at a time (written as [s, sum_of_costs, makespan]).
struct RefinePoint {
  double s = 0.0;
  std::int64_t sum_of_costs = 0, makespan = 0;
};

// One phase of a refinement on the crowd solver's roadmap (refineOnLattice);
// history: its cost over time (seconds into the phase, counted work when the
// budget counts work), the start, every 0.5% saved and the end.
struct LatticePhaseStats {
  std::int64_t sum_of_costs_before = 0, sum_of_costs_after = 0, neighbourhoods = 0, kept = 0, expansions = 0;
  std::optional<std::vector<RefinePoint>> history;
};

// A refinement on the crowd solver's roadmap: its last phase; with diagonal
// steps, sums in ticks of steps_per_tick and the step phase under axis. s and
// work_s: its wall-clock and counted-work seconds, set by the caller.
struct LatticeRefineStats : LatticePhaseStats {
  std::optional<LatticePhaseStats> axis;
  std::optional<std::int64_t> steps_per_tick;
  std::optional<double> s, work_s;
};

// The crowd solver's run (key "lacam"); the optional fields once it solved.
struct LacamStats {
  std::int64_t roadmap_vertices = 0;
  double lattice_spacing = 0.0, bounding_radius = 0.0, roadmap_s = 0.0, search_s = 0.0;
  bool grid_lattice = false;
  std::int64_t configurations = 0, expansions = 0, spread_meetings = 0;
  std::optional<std::int64_t> restarts;  // of LaCAM's search; absent in older files
  std::optional<std::int64_t> roadmap_steps, steps_per_roadmap_step, first_sum_of_costs, first_makespan;
  std::optional<double> first_solution_s;
  std::optional<LatticeRefineStats> polish;          // CrowdOptions::polish
  std::optional<LatticeRefineStats> lattice_refine;  // with CrowdOptions::refine_s
};

// compactPlan's run (key "compact").
struct CompactStats {
  double s = 0.0;
  std::int64_t passes = 0, robots_retimed = 0, steps_saved = 0, states = 0;
  bool interrupted = false;
  std::int64_t makespan_before = 0, sum_of_costs_before = 0;
  std::optional<std::string> rejected;  // why the compacted plan was not kept
};

// refinePlan's run (key "refine"); times on the plan's clock.
struct RefineStats {
  std::int64_t first_sum_of_costs = 0, first_makespan = 0, final_sum_of_costs = 0, final_makespan = 0;
  double first_s = 0.0, final_s = 0.0, budget_s = 0.0, seconds_spent = 0.0;
  std::int64_t lower_bound = 0, retimed_steps = 0, iterations = 0;
  std::int64_t shortcut_tries = 0, shortcut_improvements = 0, lns_tries = 0, lns_improvements = 0, lns_failed = 0;
  std::vector<RefinePoint> history;
  std::optional<std::int64_t> straight_line_bound;  // lower_bound is the robots' own shortest ways
  std::optional<double> lattice_s;
  std::optional<std::string> rejected;
};

// Why a scenario was refused as too large (key "too_large").
struct TooLargeStats {
  double straight_path_scalars = 0.0;
  std::int64_t limit = 0;
  std::string detail;
};

// A plan's statistics; a field is unset when the method did not report it.
// Keys no field holds (another program's, a service's) are kept in extra.
struct PlanStats {
  std::optional<double> planning_time_s;  // to the first valid plan
  std::optional<std::string> method, earc_version;
  std::optional<std::uint64_t> seed;
  std::optional<std::int64_t> makespan, sum_of_costs;  // of a valid plan
  std::optional<std::vector<std::string>> failure;      // failureCauseName of each cause
  std::optional<std::vector<std::string>> invalid_result;
  std::optional<std::string> detail, unsolved_robot, db_learn_error;
  std::optional<std::int64_t> roadmaps_reused, db_hits;
  std::optional<ArcStats> arc;
  std::optional<DatabaseStats> db;
  std::optional<LightningStats> lightning;
  std::optional<LacamStats> lacam;
  std::optional<CompactStats> compact;
  std::optional<RefineStats> refine;
  std::optional<TooLargeStats> too_large;
  nlohmann::json extra = nlohmann::json::object();

  // The JSON object written to files; fromJson(toJson()) gives the same.
  nlohmann::json toJson() const;
  // Reads any JSON object (another program's too): a field, or a group
  // whose required fields are all present, is set only when well typed.
  static PlanStats fromJson(const nlohmann::json& stats);
};

}  // namespace earc
