// PlanStats: typed fields, and a JSON form that reads back to the same text.
#include <doctest/doctest.h>

#include "earc/gen/generators.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/plan_stats.hpp"

using namespace earc;
using nlohmann::json;

namespace {

// fromJson then toJson: the same text, key for key and number for number.
void checkRoundTrip(const json& j) {
  CAPTURE(j.dump());
  CHECK(PlanStats::fromJson(j).toJson().dump() == j.dump());
}

}  // namespace

TEST_CASE("a plan's stats read back from their JSON to the same fields and text") {
  gen::MobileSettings ms;
  ms.robots = 6;
  ms.obstacles = 6;
  ms.seed = 5;
  PlannerSettings settings;
  settings.work_budgets = true;
  settings.post.compact = true;
  settings.post.refine_s = 0.2;
  const PlanResult r = plan(gen::generateMobile(ms), settings);
  REQUIRE(r.solution.solved);
  const json j = r.stats.toJson();
  CHECK(j.dump() == r.solution.stats.dump());
  checkRoundTrip(j);
  const PlanStats back = PlanStats::fromJson(j);
  REQUIRE(back.arc);
  CHECK(back.arc->conflicts == r.stats.arc->conflicts);
  CHECK(back.arc->subproblems_by_solver == r.stats.arc->subproblems_by_solver);
  CHECK(back.makespan == r.stats.makespan);
  REQUIRE(back.refine);
  CHECK(back.refine->history.size() == r.stats.refine->history.size());
  CHECK(back.compact);
  CHECK(back.method == "arc");
  CHECK(back.extra.empty());
  CHECK(j["solver_budgets"] == "work");
  CHECK(j["refine"]["history"][0].is_array());
}

TEST_CASE("every method's groups round-trip, and keys no field holds stay in extra") {
  const json j = json::parse(R"({
    "planning_time_s": 1.5, "method": "earc", "seed": 7, "earc_version": "0.1.0", "makespan": 40,
    "sum_of_costs": 90, "db_hits": 2, "db_learn_error": "disk full", "request_s": 1.75,
    "individual_paths_s": 0.1, "conflicts": 3, "subproblems": 4, "window_expansions": 1, "waits_left_out": 6,
    "subproblems_by_solver": {"database": 2, "decoupled": 2}, "subproblems_by_robots": {"2": 4},
    "solver_time_s": {"decoupled": 0.25}, "solver_budgets": "seconds", "robots_merged": 0,
    "merge_cap_raised": 0, "crowd_handovers": [{"robots": 5, "solved": true, "s": 0.5}], "crowd_s": 0.5,
    "roadmap_edge_checks": 100, "roadmaps_built": 2, "roadmap_vertices": 300, "roadmap_build_s": 0.125,
    "db_queries": 4, "db_repairs": 0, "db_refused_crowded": 1, "db_refused_too_long": 0,
    "db_skipped_unusable": 0, "db_learned": 1, "db_learned_ids": [12], "db_learn_candidates": 2,
    "db_learn_unstorable": 0, "db_learn_time_s": 0.01, "db_hit_rate": 0.5,
    "db_retrieval_time_s": 0.002, "db_row_cache_hits": 3, "db_row_cache_misses": 1,
    "db_warm_copy_hits": 1,
    "lacam": {"roadmap_vertices": 64, "lattice_spacing": 1.0, "grid_lattice": true, "bounding_radius": 0.4,
              "roadmap_s": 0.01, "search_s": 0.02, "configurations": 30, "expansions": 29,
              "spread_meetings": 0, "roadmap_steps": 12, "first_solution_s": 0.03,
              "lattice_refine": {"sum_of_costs_before": 120, "sum_of_costs_after": 100, "neighbourhoods": 3,
                                 "kept": 1, "expansions": 40, "s": 0.5, "steps_per_tick": 10,
                                 "axis": {"sum_of_costs_before": 70, "sum_of_costs_after": 60,
                                          "neighbourhoods": 9, "kept": 2, "expansions": 90,
                                          "history": [[0.0, 70, 9], [0.25, 60, 8]]}}, "steps_per_roadmap_step": 10},
    "compact": {"s": 0.01, "passes": 2, "robots_retimed": 1, "steps_saved": 4, "states": 80,
                "interrupted": false, "makespan_before": 44, "sum_of_costs_before": 94, "rejected": "x"},
    "refine": {"first_sum_of_costs": 94, "first_makespan": 44, "first_s": 1.5, "final_sum_of_costs": 90,
               "final_makespan": 40, "final_s": 1.75, "budget_s": 1.0, "lower_bound": 80, "retimed_steps": 2,
               "iterations": 5, "shortcut_tries": 3, "shortcut_improvements": 1, "lns_tries": 2,
               "lns_improvements": 1, "lns_failed": 0, "history": [[1.5, 94, 44], [1.75, 90, 40]],
               "seconds_spent": 0.25}
  })");
  checkRoundTrip(j);
  const PlanStats s = PlanStats::fromJson(j);
  REQUIRE(s.arc);
  REQUIRE(s.db);
  REQUIRE(s.lacam);
  REQUIRE(s.compact);
  REQUIRE(s.refine);
  CHECK(s.arc->crowd_handovers.at(0).robots == 5);
  CHECK(s.db->db_learned_ids == std::vector<std::int64_t>{12});
  CHECK(s.db->db_row_cache_hits == 3);
  CHECK(s.db->db_warm_copy_hits == 1);
  CHECK(s.lacam->lattice_refine->neighbourhoods == 3);
  CHECK(s.lacam->lattice_refine->s == 0.5);
  CHECK_FALSE(s.lacam->lattice_refine->work_s);
  CHECK(s.lacam->lattice_refine->axis->neighbourhoods == 9);
  CHECK(s.lacam->lattice_refine->axis->history.value().at(1).sum_of_costs == 60);
  CHECK_FALSE(s.lacam->lattice_refine->history);
  CHECK(s.compact->rejected == "x");
  CHECK(s.refine->history.at(1).makespan == 40);
  CHECK(s.db_learn_error == "disk full");
  CHECK(s.extra == json{{"request_s", 1.75}});

  const json lightning = {{"lightning_db_entries", 3}, {"lightning_source", "recall"}, {"db_hits", 1},
                          {"too_large", {{"straight_path_scalars", 1e9}, {"limit", 16}, {"detail", "big"}}}};
  checkRoundTrip(lightning);
  const PlanStats l = PlanStats::fromJson(lightning);
  CHECK(l.lightning->lightning_source == "recall");
  CHECK_FALSE(l.lightning->lightning_db_added);
  CHECK(l.too_large->limit == 16);
}

TEST_CASE("mistyped or partial stats are kept as they are, not read into the fields") {
  const json j = json::parse(R"({"planning_time_s": "soon", "makespan": -3, "sum_of_costs": 2.5,
    "conflicts": 4, "refine": {"first_s": 0.5}, "compact": 7, "failure": ["time_limit"]})");
  checkRoundTrip(j);
  const PlanStats s = PlanStats::fromJson(j);
  CHECK_FALSE(s.planning_time_s);
  CHECK_FALSE(s.makespan);
  CHECK_FALSE(s.sum_of_costs);
  CHECK_FALSE(s.arc);  // one of its keys alone
  CHECK_FALSE(s.refine);
  CHECK_FALSE(s.compact);
  CHECK(s.failure == std::vector<std::string>{"time_limit"});
  CHECK(s.extra.size() == 6);
  CHECK(PlanStats::fromJson(json::array()).toJson() == json::object());

  // A group inside a group that does not read keeps its whole group out.
  const json lacam = json::parse(R"({"lacam": {"roadmap_vertices": 4, "lattice_spacing": 1.0,
    "grid_lattice": true, "bounding_radius": 0.3, "roadmap_s": 0.0, "search_s": 0.0, "configurations": 2,
    "expansions": 1, "spread_meetings": 0, "lattice_refine": {"rounds": 3, "s": 0.5}}})");
  checkRoundTrip(lacam);
  CHECK_FALSE(PlanStats::fromJson(lacam).lacam);
}
