// The crowd suites' report (earc-bench run --suites crowd-...): per map,
// robot count and method, success, time to the first solution, cost, and
// cost over the lower bound: the sum of the robots' own shortest paths in
// steps, ignoring the others (gen::scenLowerBound; docs/benchmarks-crowds.md).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "earc/bench/results_db.hpp"

namespace earc::bench {

// Reads a solution's stats.refine (earc-plan --refine), when it has one,
// into t's refine_* fields; figures that are missing or not whole
// numbers of 0 or more (finite seconds of 0 or more) are left unset.
void readRefineStats(const nlohmann::json& stats, TrialRecord& t);

// Markdown: per crowd suite (and time limit) a row per robot count and
// method: success, medians of first-solution time, cost and cost over the
// bound (and refined cost); "" without crowd trials, which alone it shows.
std::string crowdTable(const std::vector<TrialRecord>& trials);

}  // namespace earc::bench
