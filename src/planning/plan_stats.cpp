#include "earc/planning/plan_stats.hpp"

#include <limits>
#include <type_traits>
#include <utility>

namespace earc {

namespace {

using nlohmann::json;

// Each struct's fields by their JSON keys: one list serves both ways. A
// std::optional field may be absent; any other field is required.
template <class F> void statsFields(ArcStats& s, F&& f) {
  f("individual_paths_s", s.individual_paths_s);
  f("conflicts", s.conflicts);
  f("subproblems", s.subproblems);
  f("subproblems_by_solver", s.subproblems_by_solver);
  f("subproblems_by_robots", s.subproblems_by_robots);
  f("solver_time_s", s.solver_time_s);
  f("window_expansions", s.window_expansions);
  f("waits_left_out", s.waits_left_out);
  f("window_retimed", s.window_retimed);
  f("coupled_restamped", s.coupled_restamped);
  f("coupled_restamped_around", s.coupled_restamped_around);
  f("coupled_lockstep", s.coupled_lockstep);
  f("restamped_steps", s.restamped_steps);
  f("compacted_steps", s.compacted_steps);
  f("compacted_s", s.compacted_s);
  f("solver_budgets", s.solver_budgets);
  f("robots_merged", s.robots_merged);
  f("merge_cap_raised", s.merge_cap_raised);
  f("crowd_handovers", s.crowd_handovers);
  f("crowd_s", s.crowd_s);
  f("roadmap_edge_checks", s.roadmap_edge_checks);
  f("roadmaps_built", s.roadmaps_built);
  f("roadmap_vertices", s.roadmap_vertices);
  f("roadmap_build_s", s.roadmap_build_s);
}

template <class F> void statsFields(DatabaseStats& s, F&& f) {
  f("db_queries", s.db_queries);
  f("db_repairs", s.db_repairs);
  f("db_refused_crowded", s.db_refused_crowded);
  f("db_refused_too_long", s.db_refused_too_long);
  f("db_skipped_unusable", s.db_skipped_unusable);
  f("db_learned", s.db_learned);
  f("db_learned_ids", s.db_learned_ids);
  f("db_learn_candidates", s.db_learn_candidates);
  f("db_learn_unstorable", s.db_learn_unstorable);
  f("db_learn_time_s", s.db_learn_time_s);
  f("db_retrieval_time_s", s.db_retrieval_time_s);
  f("db_row_cache_hits", s.db_row_cache_hits);
  f("db_row_cache_misses", s.db_row_cache_misses);
  f("db_warm_copy_hits", s.db_warm_copy_hits);
  f("db_hit_rate", s.db_hit_rate);
  f("db_shadow_decoupled", s.db_shadow_decoupled);
}

template <class F> void statsFields(LightningStats& s, F&& f) {
  f("lightning_db_entries", s.lightning_db_entries);
  f("lightning_db_added", s.lightning_db_added);
  f("lightning_repaired_runs", s.lightning_repaired_runs);
  f("lightning_source", s.lightning_source);
}

template <class F> void statsFields(LatticePhaseStats& s, F&& f) {
  f("sum_of_costs_before", s.sum_of_costs_before);
  f("sum_of_costs_after", s.sum_of_costs_after);
  f("neighbourhoods", s.neighbourhoods);
  f("kept", s.kept);
  f("expansions", s.expansions);
  f("history", s.history);
}

template <class F> void statsFields(LatticeRefineStats& s, F&& f) {
  statsFields(static_cast<LatticePhaseStats&>(s), f);
  f("axis", s.axis);
  f("steps_per_tick", s.steps_per_tick);
  f("s", s.s);
  f("work_s", s.work_s);
}

template <class F> void statsFields(LacamStats& s, F&& f) {
  f("roadmap_vertices", s.roadmap_vertices);
  f("lattice_spacing", s.lattice_spacing);
  f("grid_lattice", s.grid_lattice);
  f("bounding_radius", s.bounding_radius);
  f("roadmap_s", s.roadmap_s);
  f("search_s", s.search_s);
  f("configurations", s.configurations);
  f("expansions", s.expansions);
  f("spread_meetings", s.spread_meetings);
  f("restarts", s.restarts);
  f("roadmap_steps", s.roadmap_steps);
  f("first_solution_s", s.first_solution_s);
  f("first_sum_of_costs", s.first_sum_of_costs);
  f("first_makespan", s.first_makespan);
  f("polish", s.polish);
  f("lattice_refine", s.lattice_refine);
  f("steps_per_roadmap_step", s.steps_per_roadmap_step);
}

template <class F> void statsFields(CompactStats& s, F&& f) {
  f("s", s.s);
  f("passes", s.passes);
  f("robots_retimed", s.robots_retimed);
  f("steps_saved", s.steps_saved);
  f("states", s.states);
  f("interrupted", s.interrupted);
  f("makespan_before", s.makespan_before);
  f("sum_of_costs_before", s.sum_of_costs_before);
  f("rejected", s.rejected);
}

template <class F> void statsFields(RefineStats& s, F&& f) {
  f("first_sum_of_costs", s.first_sum_of_costs);
  f("first_makespan", s.first_makespan);
  f("first_s", s.first_s);
  f("final_sum_of_costs", s.final_sum_of_costs);
  f("final_makespan", s.final_makespan);
  f("final_s", s.final_s);
  f("budget_s", s.budget_s);
  f("lower_bound", s.lower_bound);
  f("straight_line_bound", s.straight_line_bound);
  f("retimed_steps", s.retimed_steps);
  f("iterations", s.iterations);
  f("shortcut_tries", s.shortcut_tries);
  f("shortcut_improvements", s.shortcut_improvements);
  f("lns_tries", s.lns_tries);
  f("lns_improvements", s.lns_improvements);
  f("lns_failed", s.lns_failed);
  f("history", s.history);
  f("seconds_spent", s.seconds_spent);
  f("lattice_s", s.lattice_s);
  f("rejected", s.rejected);
}

template <class F> void statsFields(TooLargeStats& s, F&& f) {
  f("straight_path_scalars", s.straight_path_scalars);
  f("limit", s.limit);
  f("detail", s.detail);
}

// PlanStats's own fields, each optional.
template <class F> void statsFields(PlanStats& s, F&& f) {
  f("planning_time_s", s.planning_time_s);
  f("method", s.method);
  f("earc_version", s.earc_version);
  f("seed", s.seed);
  f("makespan", s.makespan);
  f("sum_of_costs", s.sum_of_costs);
  f("failure", s.failure);
  f("invalid_result", s.invalid_result);
  f("detail", s.detail);
  f("unsolved_robot", s.unsolved_robot);
  f("db_learn_error", s.db_learn_error);
  f("roadmaps_reused", s.roadmaps_reused);
  f("db_hits", s.db_hits);
}

// Groups inside a group: read and written whole (defined below).
bool readStat(const json& v, LatticePhaseStats& out);
bool readStat(const json& v, LatticeRefineStats& out);
json statJson(const LatticePhaseStats& s);
json statJson(const LatticeRefineStats& s);

// Reading one value: false when v is not of the field's type. Counts are
// whole numbers of 0 and more that fit an int64.
bool readStat(const json& v, double& out) {
  if (!v.is_number()) return false;
  out = v.get<double>();
  return true;
}
bool readStat(const json& v, std::int64_t& out) {
  if (v.is_number_unsigned()) {
    if (v.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) return false;
  } else if (!v.is_number_integer() || v.get<std::int64_t>() < 0) {
    return false;
  }
  out = v.get<std::int64_t>();
  return true;
}
bool readStat(const json& v, std::uint64_t& out) {
  if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<std::int64_t>() >= 0)) return false;
  out = v.get<std::uint64_t>();
  return true;
}
bool readStat(const json& v, bool& out) {
  if (!v.is_boolean()) return false;
  out = v.get<bool>();
  return true;
}
bool readStat(const json& v, std::string& out) {
  if (!v.is_string()) return false;
  out = v.get<std::string>();
  return true;
}
bool readStat(const json& v, json& out) {
  out = v;
  return true;
}
bool readStat(const json& v, RefinePoint& out) {
  return v.is_array() && v.size() == 3 && readStat(v[0], out.s) && readStat(v[1], out.sum_of_costs) &&
         readStat(v[2], out.makespan);
}
bool readStat(const json& v, CrowdHandover& out) {
  return v.is_object() && v.size() == 3 && v.contains("robots") && readStat(v["robots"], out.robots) &&
         v.contains("solved") && readStat(v["solved"], out.solved) && v.contains("s") && readStat(v["s"], out.s);
}
template <class T> bool readStat(const json& v, std::vector<T>& out) {
  if (!v.is_array()) return false;
  out.assign(v.size(), T{});
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!readStat(v[i], out[i])) return false;
  return true;
}
template <class T> bool readStat(const json& v, std::map<std::string, T>& out) {
  if (!v.is_object()) return false;
  out.clear();
  for (const auto& [key, value] : v.items())
    if (!readStat(value, out[key])) return false;
  return true;
}

json statJson(const RefinePoint& p) { return json::array({p.s, p.sum_of_costs, p.makespan}); }
json statJson(const CrowdHandover& h) { return {{"robots", h.robots}, {"solved", h.solved}, {"s", h.s}}; }
template <class T> json statJson(const T& value) { return json(value); }
template <class T> json statJson(const std::vector<T>& values) {
  json out = json::array();
  for (const T& v : values) out.push_back(statJson(v));
  return out;
}

template <class T> struct IsOptional : std::false_type {};
template <class T> struct IsOptional<std::optional<T>> : std::true_type {};

// The fields of `group` as keys of `out`; unset optional ones left out.
template <class G> void writeStats(const G& group, json& out) {
  statsFields(const_cast<G&>(group), [&](const char* key, const auto& field) {
    using T = std::decay_t<decltype(field)>;
    if constexpr (IsOptional<T>::value) {
      if (field) out[key] = statJson(*field);
    } else {
      out[key] = statJson(field);
    }
  });
}

// Reads the fields of a G from `rest`, taking their keys out of it. A
// required field missing or mistyped gives nothing and leaves `rest` as it
// was; a mistyped optional field stays in `rest`, unset.
template <class G> std::optional<G> takeStats(json& rest) {
  G group;
  bool complete = true;
  std::vector<const char*> taken;
  statsFields(group, [&](const char* key, auto& field) {
    using T = std::decay_t<decltype(field)>;
    const auto it = rest.find(key);
    if constexpr (IsOptional<T>::value) {
      typename T::value_type value{};
      if (it != rest.end() && readStat(*it, value)) {
        field = std::move(value);
        taken.push_back(key);
      }
    } else {
      if (it != rest.end() && readStat(*it, field))
        taken.push_back(key);
      else
        complete = false;
    }
  });
  if (!complete) return std::nullopt;
  for (const char* key : taken) rest.erase(key);
  return group;
}

// A group under its own key: taken only when the whole object reads.
template <class G> std::optional<G> takeNestedStats(json& rest, const char* key) {
  const auto it = rest.find(key);
  if (it == rest.end() || !it->is_object()) return std::nullopt;
  json inner = *it;
  std::optional<G> group = takeStats<G>(inner);
  if (!group || !inner.empty()) return std::nullopt;
  rest.erase(key);
  return group;
}

template <class G> bool readGroup(const json& v, G& out) {
  if (!v.is_object()) return false;
  json inner = v;
  std::optional<G> group = takeStats<G>(inner);
  if (!group || !inner.empty()) return false;
  out = *group;
  return true;
}
bool readStat(const json& v, LatticePhaseStats& out) { return readGroup(v, out); }
bool readStat(const json& v, LatticeRefineStats& out) { return readGroup(v, out); }

template <class G> json groupJson(const G& group) {
  json out = json::object();
  writeStats(group, out);
  return out;
}
json statJson(const LatticePhaseStats& s) { return groupJson(s); }
json statJson(const LatticeRefineStats& s) { return groupJson(s); }

}  // namespace

json PlanStats::toJson() const {
  json out = extra.is_object() ? extra : json::object();
  writeStats(*this, out);
  if (arc) writeStats(*arc, out);
  if (db) writeStats(*db, out);
  if (lightning) writeStats(*lightning, out);
  const auto nested = [&](const char* key, const auto& group) {
    if (!group) return;
    json inner = json::object();
    writeStats(*group, inner);
    out[key] = std::move(inner);
  };
  nested("lacam", lacam);
  nested("compact", compact);
  nested("refine", refine);
  nested("too_large", too_large);
  return out;
}

PlanStats PlanStats::fromJson(const json& stats) {
  PlanStats s;
  if (!stats.is_object()) return s;
  json rest = stats;
  s = *takeStats<PlanStats>(rest);
  s.arc = takeStats<ArcStats>(rest);
  s.db = takeStats<DatabaseStats>(rest);
  s.lightning = takeStats<LightningStats>(rest);
  s.lacam = takeNestedStats<LacamStats>(rest, "lacam");
  s.compact = takeNestedStats<CompactStats>(rest, "compact");
  s.refine = takeNestedStats<RefineStats>(rest, "refine");
  s.too_large = takeNestedStats<TooLargeStats>(rest, "too_large");
  s.extra = std::move(rest);
  return s;
}

}  // namespace earc
