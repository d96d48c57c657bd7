// --seed and --time-limit of earc-bench table, export and plot: which
// trials they take, as a bench::TrialFilter filled in by the parse.
#pragma once

#include "earc/bench/report.hpp"
#include "earc/cli/subcommands.hpp"

namespace earc {

inline void addTrialFilterOptions(CLI::App& cmd, bench::TrialFilter& filter) {
  cmd.add_option("--seed", filter.seed, "Only trials of this run seed")->check(cli::kWholeNumber);
  cmd.add_option("--time-limit", filter.time_limit_s, "Only trials with this time limit")->check(cli::kFinitePositive);
}

}  // namespace earc
