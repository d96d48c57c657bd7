// earc-bench table: the results as markdown: success rate and median
// planning time (IQR) per suite, robot count and method, the E-ARC/ARC
// ratio paired by seed, and the databases; a table per time limit where a
// suite ran under several; then, for crowd suites, cost against the lower
// bound (bench/crowds.hpp).
//
//   earc-bench table --results FILE [--seed S] [--time-limit S] [--wide]
#include <iostream>

#include "earc/bench/crowds.hpp"
#include "earc/bench/report.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/cli/subcommands.hpp"
#include "trial_filter_options.hpp"

namespace earc {
namespace {

struct TableOptions {
  std::string results;
  bench::TrialFilter filter;
  bool wide = false;
};

void setupTable(CLI::App& app) {
  auto o = std::make_shared<TableOptions>();
  auto* cmd = app.add_subcommand("table", "Print the results as a markdown table");
  cmd->add_option("--results", o->results, "Results database")->check(earc::cli::kFileName)->required();
  addTrialFilterOptions(*cmd, o->filter);
  cmd->add_flag("--wide", o->wide,
                "One table per suite laid out like the paper's figures: a row per robot count, a column per method, "
                "the paired E-ARC/ARC ratio and E-ARC's hit rate");
  cmd->callback([o] {
    bench::ResultsDb db(o->results, true);
    const std::vector<bench::TrialRecord> trials = o->filter.applyRequired(db.recordedTrials(), o->results);
    std::cout << (o->wide ? bench::markdownWideTable(trials) : bench::markdownTable(trials, db.databases()))
              << bench::crowdTable(trials);
  });
}

cli::Registrar registered_table("earc-bench", "table", setupTable);

}  // namespace
}  // namespace earc
