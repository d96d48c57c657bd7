// earc-bench table: the results as markdown: success rate and median
// planning time (IQR) per suite, robot count and method, the E-ARC/ARC
// ratio paired by seed, and the databases; a table per time limit where a
// suite ran under several.
//
//   earc-bench table --results FILE [--seed S] [--time-limit S] [--wide]
#include <iostream>

#include "earc/bench/report.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/util/subcommands.hpp"

namespace earc {
namespace {

struct TableOptions {
  std::string results;
  std::uint64_t seed = 0;
  double time_limit = 0;
  bool wide = false;
};

void setupTable(CLI::App& app) {
  auto o = std::make_shared<TableOptions>();
  auto* cmd = app.add_subcommand("table", "Print the results as a markdown table");
  cmd->add_option("--results", o->results, "Results database")->check(earc::cli::kFileName)->required();
  auto* seed = cmd->add_option("--seed", o->seed, "Only trials of this run seed")->check(earc::cli::kWholeNumber);
  auto* limit = cmd->add_option("--time-limit", o->time_limit, "Only trials with this time limit")
                    ->check(earc::cli::kFinitePositive);
  cmd->add_flag("--wide", o->wide,
                "One table per suite laid out like the paper's figures: a row per robot count, a column per method, "
                "the paired E-ARC/ARC ratio and E-ARC's hit rate");
  cmd->callback([o, seed, limit] {
    bench::ResultsDb db(o->results, true);
    bench::TrialFilter f;
    if (seed->count()) f.seed = o->seed;
    if (limit->count()) f.time_limit_s = o->time_limit;
    const std::vector<bench::TrialRecord> trials = f.applyRequired(db.trials(), o->results);
    std::cout << (o->wide ? bench::markdownWideTable(trials) : bench::markdownTable(trials, db.databases()));
  });
}

cli::Registrar registered_table("earc-bench", "table", setupTable);

}  // namespace
}  // namespace earc
