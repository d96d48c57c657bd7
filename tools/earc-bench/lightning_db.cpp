// earc-bench lightning-db: grow a Lightning database (OMPL's file) from
// random problems of one suite and robot count, timing the construction.
//
//   earc-bench lightning-db --robots N --family mobile|arms [--obstacles]
//     --count M [--seed S] [--problem-time-limit S] -o FILE [--append]
//     [--results FILE.sqlite]
//   earc-bench lightning-db --scenario FILE --count M ...
//
// With --scenario the problems are the file's robots in its world at
// random starts and goals (bench::fileDatabaseProblem): the database for
// earc-bench run's trials of that file, and of every file that differs
// from it only in starts and goals.
//
// The problems are generated like the suites' trials but from a stream of
// the seed that trials never use (bench::databaseProblem). Construction
// time is the wall time of planning all M problems, solved or not: what
// growing the database costs.
#include <filesystem>
#include <iostream>
#include <optional>

#include "earc/baselines/lightning.hpp"
#include "earc/bench/options.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/bench/suites.hpp"
#include "earc/cli/stop_signals.hpp"
#include "earc/cli/subcommands.hpp"
#include "earc/io/input_error.hpp"
#include "earc/util/deadline.hpp"
#include "earc/util/progress.hpp"
#include "earc/util/random.hpp"

namespace earc {
namespace {

struct LightningDbOptions {
  std::string scenario;
  std::string suite;
  std::string family = "mobile";
  bool obstacles = false;
  int robots = 2;
  int count = 10;
  std::uint64_t seed = 1;
  double problem_time_limit = 10.0;
  std::string output;
  bool append = false;
  std::string results;
};

const bench::Suite& chooseSuite(const LightningDbOptions& o) {
  if (!o.suite.empty()) return bench::suiteByName(o.suite, "--suite");
  return bench::suiteByName(o.family + (o.obstacles ? "-obst" : ""));
}

// Exit status: 0, or 128 + the signal's number after Ctrl-C or SIGTERM,
// which stop the problem being planned and leave every file as it was.
int runLightningDb(const LightningDbOptions& o) {
  // A scenario file's world, or a suite.
  std::optional<bench::ScenarioFile> file;
  if (!o.scenario.empty()) file = std::move(bench::loadScenarioFiles({o.scenario}).front());
  const bench::Suite* suite = file ? nullptr : &chooseSuite(o);
  const std::string suite_name = file ? bench::kFilesSuite : suite->name;
  const int robots = file ? file->robots() : o.robots;
  auto problem = [&](int i) {
    return file ? bench::fileDatabaseProblem(*file, i, o.seed) : bench::databaseProblem(*suite, robots, i, o.seed);
  };
  const bool exists = std::filesystem::exists(o.output);
  if (exists && !o.append) throw InputError(o.output, "-o", "exists; pass --append to grow it");
  // The results database is opened (checked, or created) before the
  // minutes of planning: a bad one must not throw their work away.
  std::optional<bench::ResultsDb> results;
  if (!o.results.empty()) {
    bench::requireSeparateOutputs(o.results, "--results", {{o.output, "-o"}});
    results.emplace(o.results);
  }

  Scenario first = problem(0);
  LightningDatabase db(first);
  if (exists) db.load(o.output);
  const std::size_t before = db.entries();
  LightningSettings ls;
  ls.learn = true;
  cli::StopSignals signals;
  PlanContext context;
  context.stop = &signals.flag();
  Progress progress("lightning-db", static_cast<std::size_t>(o.count));
  int solved = 0, recalled = 0, planned = 0;
  Stopwatch clock;
  for (int i = 0; i < o.count && !stopSet(context.stop); ++i) {
    Scenario s = i == 0 ? first : problem(i);
    PlannerSettings ps;
    ps.method = Method::Lightning;
    ps.time_limit_s = o.problem_time_limit;
    ps.seed = splitSeed(o.seed, static_cast<std::uint64_t>(i));
    PlanResult r = db.plan(s, ps, ls, context);
    if (stopSet(context.stop)) break;
    ++planned;
    if (r.solution.solved) ++solved;
    if (r.stats.lightning && r.stats.lightning->lightning_source == "recall") ++recalled;
    progress.setStatus(std::to_string(db.entries()) + " entries");
    progress.tick();
  }
  const double construction = clock.seconds();
  progress.finish();
  if (signals.signal() != 0) {
    // A database of fewer problems than asked, timed as if whole, would
    // mislead: nothing is written.
    std::cerr << "earc-bench lightning-db: interrupted (" << signals.signalName() << ") after " << planned << " of "
              << o.count << " problems; nothing written\n";
    return signals.exitCode();
  }
  db.save(o.output);
  const auto size = static_cast<std::int64_t>(std::filesystem::file_size(o.output));
  std::cout << o.output << ": " << db.entries() << " entries (" << db.entries() - before << " new, " << db.states()
            << " states), " << size << " bytes; " << o.count << " problems of "
            << (file ? "the world of " + file->path : suite_name) << " with " << robots
            << " robots, " << solved << " solved (" << recalled << " from recall); construction " << construction
            << " s\n";
  if (results) {
    bench::DatabaseRecord d;
    d.method = "lightning";
    d.suite = suite_name;
    d.robots = robots;
    d.path = o.output;
    d.construction_time_s = construction;
    d.entries = static_cast<std::int64_t>(db.entries());
    d.size_bytes = size;
    d.problems = o.count;
    d.seed = o.seed;
    results->addDatabase(d);
  }
  return 0;
}

void setupLightningDb(CLI::App& app) {
  auto o = std::make_shared<LightningDbOptions>();
  auto* cmd = app.add_subcommand("lightning-db", "Grow a Lightning database from random problems of one size, timed");
  auto* scenario = cmd->add_option("--scenario", o->scenario,
                                   "Problems in this scenario's world (its robots at random starts and goals) instead of a suite's")
                       ->check(earc::cli::kFileName);
  auto* robots = cmd->add_option("--robots,-n", o->robots, "Robots per problem")->check(earc::cli::wholeNumberIn(2, bench::kMaxResultsRobots))->capture_default_str();
  auto* family = cmd->add_option("--family", o->family, "mobile or arms")->check(CLI::IsMember({"mobile", "arms"}))->capture_default_str();
  auto* obstacles = cmd->add_flag("--obstacles", o->obstacles, "Random obstacles, as in the -obst suites");
  auto* suite = cmd->add_option("--suite", o->suite, "A suite name instead of --family/--obstacles");
  for (auto* other : {robots, family, obstacles, suite}) scenario->excludes(other);
  cmd->add_option("--count", o->count, "Problems to plan")->check(earc::cli::kPositiveWholeNumber)->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed of the problems and the planners")->check(earc::cli::kWholeNumber)->capture_default_str();
  cmd->add_option("--problem-time-limit", o->problem_time_limit, "Seconds per problem")
      ->check(earc::cli::kFinitePositive)
      ->capture_default_str();
  cmd->add_option("-o,--output", o->output, "Database file (OMPL Lightning format)")->check(earc::cli::kFileName)->required();
  cmd->add_flag("--append", o->append, "Grow an existing database");
  cmd->add_option("--results", o->results, "Record construction time, entries and size in this results database");
  cmd->callback([o] { cli::setExitCode(runLightningDb(*o)); });
}

cli::Registrar registered_lightning_db("earc-bench", "lightning-db", setupLightningDb);

}  // namespace
}  // namespace earc
