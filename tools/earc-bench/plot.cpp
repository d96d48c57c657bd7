// earc-bench plot: figures from a results database, drawn by
// tools/plots/plot_results.py (matplotlib) run with /usr/bin/python3: per
// suite, and per time limit where a suite ran under several, as table
// makes a table per limit.
//
//   earc-bench plot --results FILE -o DIR [--seed S] [--time-limit S] [--python PATH] [--script PATH]
#include <filesystem>
#include <iostream>

#include "earc/bench/child.hpp"
#include "earc/bench/options.hpp"
#include "earc/bench/report.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/cli/subcommands.hpp"
#include "earc/io/input_error.hpp"
#include "earc/util/format.hpp"
#include "trial_filter_options.hpp"

namespace earc {
namespace {

// Drawing a few dozen figures takes seconds; ten minutes is a hang.
constexpr double kPlotWallLimitS = 600.0;

struct PlotOptions {
  std::string results;
  std::string output;
  std::string python = "/usr/bin/python3";
  std::string script = std::string(EARC_SOURCE_DIR) + "/tools/plots/plot_results.py";
  bench::TrialFilter filter;
};

void setupPlot(CLI::App& app) {
  auto o = std::make_shared<PlotOptions>();
  auto* cmd = app.add_subcommand("plot", "Plot results (PNG and SVG) with tools/plots/plot_results.py");
  cmd->add_option("--results", o->results, "Results database")->check(earc::cli::kFileName)->required();
  cmd->add_option("-o,--output", o->output, "Directory for the figures")->check(earc::cli::kFileName)->required();
  cmd->add_option("--python", o->python, "Python with matplotlib and numpy")->capture_default_str();
  cmd->add_option("--script", o->script, "The plotting script")->capture_default_str();
  // As table and export take them (TrialFilter); the script selects the
  // same trials.
  addTrialFilterOptions(*cmd, o->filter);
  cmd->callback([o] {
    if (!std::filesystem::exists(o->results)) throw InputError(o->results, "--results", "no such file");
    // The checks table and export make (a foreign file, a newer schema, a
    // row no run writes), with their messages, before Python runs.
    {
      const bench::ResultsDb check(o->results, true);
      o->filter.applyRequired(check.recordedTrials(), o->results);
    }
    bench::requireOutputDirectory(o->output, "-o");
    if (!std::filesystem::exists(o->script)) throw InputError(o->script, "--script", "no such file");
    bench::requireExecutable(o->python, "--python");
    bench::ChildSpec spec;
    spec.argv = {o->python, o->script, "--results", o->results, "-o", o->output};
    if (o->filter.seed) spec.argv.insert(spec.argv.end(), {"--seed", std::to_string(*o->filter.seed)});
    // Digits enough to round-trip: the script's float is this very double,
    // which it compares with the stored limits as table does.
    if (o->filter.time_limit_s)
      spec.argv.insert(spec.argv.end(), {"--time-limit", exactNumber(*o->filter.time_limit_s)});
    spec.wall_limit_s = kPlotWallLimitS;
    spec.inherit_output = true;
    bench::ChildOutcome out = bench::runChild(spec);
    // Exit 1 or 2: the script said why, in one line of its own.
    if (out.exit_code == 1 || out.exit_code == 2) cli::setExitCode(*out.exit_code);
    else if (out.killed_at_limit)
      throw std::runtime_error(o->script + ": the plotting script did not finish in " +
                               std::to_string(static_cast<int>(kPlotWallLimitS)) + " s");
    else if (out.exit_code != 0)
      throw std::runtime_error(o->script + ": the plotting script failed (" +
                               (out.signal ? "signal " + std::to_string(*out.signal)
                                           : "exit " + std::to_string(out.exit_code.value_or(-1))) +
                               ")");
  });
}

cli::Registrar registered_plot("earc-bench", "plot", setupPlot);

}  // namespace
}  // namespace earc
