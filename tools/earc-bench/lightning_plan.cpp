// earc-bench lightning-plan: `earc-plan plan --method lightning` with a
// Lightning database file, which earc-plan has no option for. Same contract:
// writes the solution, exit 0 solved (validated), 1 not solved, 2 bad input.
//
//   earc-bench lightning-plan SCENARIO -o SOLUTION [--db FILE] [--no-learn]
//     [--time-limit S] [--seed K] [-q]
#include <filesystem>
#include <iostream>

#include "earc/baselines/lightning.hpp"
#include "earc/io/json_io.hpp"
#include "earc/util/subcommands.hpp"

namespace earc {
namespace {

struct LightningPlanOptions {
  std::string scenario;
  std::string output;
  std::string db;
  bool no_learn = false;
  double time_limit = 60.0;
  std::uint64_t seed = 1;
  bool quiet = false;
};

int runLightningPlan(const LightningPlanOptions& o) {
  Scenario scenario = loadScenario(o.scenario);
  if (!(o.time_limit > 0)) throw InputError("", "--time-limit", "must be a positive number of seconds");
  if (!o.db.empty() && o.no_learn && !std::filesystem::exists(o.db))
    throw InputError(o.db, "--db", "no such Lightning database (build one with earc-bench lightning-db)");
  PlannerSettings s;
  s.method = Method::Lightning;
  s.time_limit_s = o.time_limit;
  s.seed = o.seed;
  LightningSettings ls;
  ls.db_path = o.db;
  ls.learn = !o.no_learn;
  PlanResult r = planLightningChecked(scenario, s, ls);
  saveSolution(o.output, r.solution);
  if (!o.quiet) {
    const auto& st = r.stats;
    if (r.solution.solved)
      std::cout << "solved: " << scenario.robots.size() << " robots, lightning (" << st.value("lightning_source", "?")
                << "), " << st.value("planning_time_s", 0.0) << " s, database " << st.value("lightning_db_entries", 0)
                << " entries\n";
    else
      std::cout << "not solved: " << st.value("failure", nlohmann::json::array()).dump() << " after "
                << st.value("planning_time_s", 0.0) << " s\n";
    std::cout << "solution: " << o.output << "\n";
  }
  return r.solution.solved ? 0 : 1;
}

void setupLightningPlan(CLI::App& app) {
  auto o = std::make_shared<LightningPlanOptions>();
  auto* cmd = app.add_subcommand("lightning-plan",
                                 "Plan a scenario with Lightning and a database file (exit 0 solved, 1 not solved)");
  cmd->add_option("scenario", o->scenario, "Scenario JSON file")->required();
  cmd->add_option("-o,--output", o->output, "Solution JSON file to write")->required();
  cmd->add_option("--db", o->db, "Lightning database (OMPL format; created when missing unless --no-learn)");
  cmd->add_flag("--no-learn", o->no_learn, "Leave the database as it is");
  cmd->add_option("--time-limit", o->time_limit, "Planning time limit in seconds")->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed for every random choice")->capture_default_str();
  cmd->add_flag("-q,--quiet", o->quiet, "Print nothing");
  cmd->callback([o] { cli::setExitCode(runLightningPlan(*o)); });
}

cli::Registrar reg("earc-bench", "lightning-plan", setupLightningPlan);

}  // namespace
}  // namespace earc
