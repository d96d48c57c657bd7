// earc-bench export: results as CSV and as OMPL benchmark logs.
//
//   earc-bench export --results FILE [--csv OUT.csv] [--databases-csv OUT.csv]
//     [--ompl-log DIR] [--seed S] [--time-limit S]
//
// The OMPL logs (one per suite, robot count and time limit; planners are the
// methods) load with ompl_benchmark_statistics.py DIR/*.log -d OUT.db and
// so into Planner Arena.
#include <iostream>
#include <sstream>

#include "earc/bench/options.hpp"
#include "earc/bench/report.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/cli/subcommands.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "trial_filter_options.hpp"

namespace earc {
namespace {

struct ExportOptions {
  std::string results;
  std::string csv, databases_csv, ompl_dir;
  bench::TrialFilter filter;
};


void setupExport(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  auto* cmd = app.add_subcommand("export", "Write results as CSV and as OMPL benchmark logs");
  cmd->add_option("--results", o->results, "Results database")->check(earc::cli::kFileName)->required();
  cmd->add_option("--csv", o->csv, "One row per trial");
  cmd->add_option("--databases-csv", o->databases_csv, "One row per database");
  cmd->add_option("--ompl-log", o->ompl_dir, "Directory for OMPL benchmark logs (one per suite and robot count)");
  addTrialFilterOptions(*cmd, o->filter);
  cmd->callback([o] {
    if (o->csv.empty() && o->databases_csv.empty() && o->ompl_dir.empty())
      throw InputError("", "--csv/--databases-csv/--ompl-log", "nothing to export: give at least one");
    bench::ResultsDb db(o->results, true);
    const std::vector<bench::TrialRecord> trials = o->filter.applyRequired(db.recordedTrials(), o->results);
    // Before anything is written: no output may overwrite the results or
    // another output.
    std::vector<std::pair<std::string, std::string>> outputs = {
        {o->csv, "--csv"}, {o->databases_csv, "--databases-csv"}, {o->ompl_dir, "--ompl-log"}};
    if (!o->ompl_dir.empty()) {
      bench::requireOutputDirectory(o->ompl_dir, "--ompl-log");
      for (const std::string& f : bench::omplLogFiles(trials, o->ompl_dir)) outputs.emplace_back(f, "--ompl-log");
    }
    bench::requireSeparateOutputs(o->results, "--results", outputs);
    // A CSV on stdout itself (--csv /dev/stdout) must not get the summary
    // lines in among its rows: they go to stderr then.
    std::ostream& summary = summaryStream({o->csv, o->databases_csv});
    if (!o->csv.empty()) {
      // Written whole, as every output (docs/formats.md: a killed command leaves
      // no half file).
      std::ostringstream out;
      bench::writeCsv(trials, out);
      writeTextFileAtomic(o->csv, out.str());
      summary << o->csv << ": " << trials.size() << " trials\n";
    }
    if (!o->databases_csv.empty()) {
      std::ostringstream out;
      const auto dbs = db.databases();
      bench::writeDatabasesCsv(dbs, out);
      writeTextFileAtomic(o->databases_csv, out.str());
      summary << o->databases_csv << ": " << dbs.size() << " databases\n";
    }
    if (!o->ompl_dir.empty())
      for (const std::string& f : bench::writeOmplLogs(trials, o->ompl_dir)) summary << f << "\n";
  });
}

cli::Registrar registered_export("earc-bench", "export", setupExport);

}  // namespace
}  // namespace earc
