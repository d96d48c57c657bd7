// earc-bench run: the E-ARC paper's experiments (see earc/bench/runner.hpp).
//
//   earc-bench run [--suites mobile,mobile-obst,arms,arms-obst|crowd|...] [--robots 2,4,8]
//     [--methods earc,arc,lightning,prioritized,coupled,lacam] [--trials N]
//     [--time-limit S] [--seed S] [--results FILE.sqlite] [--db-mobile FILE]
//     [--db-arms FILE] [--lightning-dir DIR] [--jobs N] [--full]
//     [--method-arg METHOD=ARG]... [--refine S] [SCENARIO...]
//
// Scenario files given instead of suites are the trials (suite "files",
// one trial per file and method).
//
// Exit status 0 when the run finished (failed trials are results, not
// errors), 1 when some solution was INVALID, 2 for bad options, 130 when
// interrupted (run the same command again to resume).
#include <algorithm>
#include <iostream>
#include <map>

#include "earc/bench/options.hpp"
#include "earc/bench/runner.hpp"
#include "earc/bench/suites.hpp"
#include "earc/cli/subcommands.hpp"
#include "earc/io/input_error.hpp"
#include "earc/util/format.hpp"

namespace earc {
namespace {

// --full: every suite, robot count and method, 20 trials per cell.
constexpr int kFullTrials = 20;

struct RunCli {
  bench::RunOptions run;
  std::string suites, robots, methods;
  std::vector<std::string> method_args;  // METHOD=ARG
  double refine = 0.0;                   // --refine S, passed to every plan
  bool full = false;
};

std::vector<int> parseCounts(const std::string& list) {
  std::vector<int> out;
  for (const std::string& item : bench::splitOptionList(list, "--robots")) {
    try {
      std::size_t used = 0;
      int n = std::stoi(item, &used);
      if (used != item.size() || n < 2) throw std::invalid_argument(item);
      out.push_back(n);
    } catch (const std::exception&) {
      throw InputError("", "--robots", "'" + item + "' is not a robot count (2 or more)");
    }
  }
  return out;
}

bool isCrowdSuite(const std::string& name) {
  for (const bench::Suite& s : bench::allSuites())
    if (s.name == name) return s.crowd();
  return false;
}

// "crowd-empty-16-16, ...".
std::string crowdSuiteNames() {
  std::string names;
  for (const bench::Suite& s : bench::allSuites())
    if (s.crowd()) names += (names.empty() ? "" : ", ") + s.name;
  return names;
}

// --suites with "crowd" standing for every crowd suite.
std::vector<std::string> expandCrowd(const std::vector<std::string>& given) {
  std::vector<std::string> out;
  for (const std::string& name : given) {
    if (name != "crowd") {
      out.push_back(name);
      continue;
    }
    for (const bench::Suite& s : bench::allSuites())
      if (s.crowd()) out.push_back(s.name);
  }
  return out;
}

// --method-arg METHOD=ARG, in the order given, by method; METHOD is
// checked with the other options (runBenchmark), ARG by
// plannerArgsProblem there.
std::map<std::string, std::vector<std::string>> parseMethodArgs(const std::vector<std::string>& given) {
  std::map<std::string, std::vector<std::string>> out;
  for (const std::string& item : given) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("", "--method-arg", "'" + printableText(item, 80) + "' is not METHOD=ARG (earc=--db-k=5)");
    out[item.substr(0, eq)].push_back(item.substr(eq + 1));
  }
  return out;
}

void setupRun(CLI::App& app) {
  auto o = std::make_shared<RunCli>();
  bench::RunOptions& r = o->run;
  auto* cmd = app.add_subcommand(
      "run", "Run the paper's experiments, or every method on your scenario files: trials per (suite, robots, method), "
             "each in its own process; resumable");
  cmd->add_option("scenarios", r.scenario_files,
                  "Scenario files to run instead of the suites: one trial per file and method (suite 'files'); "
                  "E-ARC's database is built for their robots")
      ->check(earc::cli::kFileName);
  auto* suites = cmd->add_option("--suites", o->suites, "Suites: mobile, mobile-obst, arms, arms-obst (the paper's), movingai-random, movingai-den520d "
                  "(MovingAI maps), " + crowdSuiteNames() + " (crowds: a MovingAI scenario file's first N agents; "
                  "'crowd' for all four) (default mobile-obst,arms)");
  auto* robots = cmd->add_option("--robots", o->robots, "Robot counts (default 2,4,8; with --full, or crowd suites "
                  "alone, every count of the suite; a crowd suite takes any count up to its file's agents)");
  auto* methods = cmd->add_option("--methods", o->methods,
                                  "Methods: " + bench::allMethodsText() + " (default earc,arc,lightning,prioritized)");
  auto* trials = cmd->add_option("--trials", r.trials, "Trials per cell (default 2; --full: 20)")
                     ->check(earc::cli::kPositiveWholeNumber);
  cmd->add_option("--time-limit", r.time_limit_s, "Planning time limit per trial, seconds")
      ->check(earc::cli::kFinitePositive)
      ->capture_default_str();
  cmd->add_option("--seed", r.seed, "Seed of the run: scenarios and planner seeds derive from it")->check(earc::cli::kWholeNumber)->capture_default_str();
  cmd->add_option("--results", r.results, "Results database (SQLite), appended to and resumed from")->capture_default_str();
  cmd->add_option("--work-dir", r.work_dir, "Scenarios, failed trials' solutions and logs (default RESULTS.work)");
  cmd->add_option("--db-mobile", r.db_mobile,
                  "E-ARC database for the mobile suites (earc-plan --db); built with earc-db build when missing "
                  "(default: one built in the work directory, named by what its rows come of: "
                  "WORK/earc-mobile[-pCOUNT]-sSEED[-learn].sqlite)");
  cmd->add_option("--db-arms", r.db_arms,
                  "E-ARC database for the arm suites (default WORK/earc-arms[-pCOUNT]-sSEED[-learn].sqlite)");
  cmd->add_option("--earc-db-count", r.earc_db_count,
                  "Problems for the E-ARC databases the run builds itself (default: earc-db's); not with "
                  "--db-mobile or --db-arms")
      ->check(earc::cli::kPositiveWholeNumber);
  cmd->add_option("--lightning-dir", r.lightning_dir,
                  "Lightning databases, built here when missing and named by what grows them: "
                  "SUITE-ROBOTS-pPROBLEMS-tLIMIT-sSEED[-learn].lightning (default WORK/lightning)");
  cmd->add_option("--lightning-problems", r.lightning_problems, "Problems per Lightning database (default 4 x robots)")
      ->check(earc::cli::kPositiveWholeNumber);
  cmd->add_option("--lightning-problems-per-robot", r.lightning_problems_per_robot,
                  "Problems per robot for a Lightning database")
      ->check(earc::cli::kPositiveWholeNumber)
      ->capture_default_str();
  cmd->add_option("--lightning-problem-time-limit", r.lightning_problem_time_limit_s,
                  "Time limit per problem while building a Lightning database")
      ->check(earc::cli::kFinitePositive)
      ->capture_default_str();
  cmd->add_option("--jobs", r.jobs,
                  "Trials run at once. Default 1: concurrent trials share cores and memory bandwidth and disturb "
                  "each other's timings")
      ->check(earc::cli::kPositiveWholeNumber)
      ->capture_default_str();
  cmd->add_option("--memory-limit-mb", r.memory_limit_mb, "Address-space limit of each trial's process (MiB)")
      ->check(earc::cli::kPositiveWholeNumber)
      ->capture_default_str();
  cmd->add_option("--wall-margin", r.wall_margin_s,
                  "Seconds a trial's process may run past its time limit before SIGKILL (default 15 + 25% of it)")
      ->check(earc::cli::kFiniteNonNegative);
  cmd->add_option("--plan-program", r.plan_program, "The earc-plan to run (default: the one next to earc-bench)");
  cmd->add_option("--method-arg", o->method_args,
                  "METHOD=ARG: one argument added to every earc-plan plan of METHOD and recorded with its trials "
                  "(repeatable: earc=--db-k=5 arc=--window=4; an option and its value as two: earc=--window earc=4)");
  cmd->add_option("--refine", o->refine,
                  "Seconds each plan spends refining its first valid plan (earc-plan plan --refine, within the time "
                  "limit; recorded with the trials as a method argument; default 0: off)")
      ->check(earc::cli::kFiniteNonNegative);
  auto* full = cmd->add_flag("--full", o->full, "The paper's experiments: its four suites, all robot counts and methods, 20 trials per cell "
                "(with --suites: those suites instead)");
  cmd->add_flag("--learn", r.learn, "Let E-ARC and Lightning add to their databases during trials (default: fixed databases)");
  cmd->add_flag("--keep-solutions", r.keep_solutions, "Keep the solution files of solved trials");
  cmd->add_flag("-v,--verbose", r.verbose, "One line per finished trial");
  cmd->add_flag("--cutoff", r.cutoff,
                "Skip a method at larger robot counts of a suite once it solved none of the trials at a smaller one");
  cmd->callback([o, suites, robots, methods, trials, full] {
    bench::RunOptions& r = o->run;
    if (!r.scenario_files.empty())
      for (const CLI::Option* opt : {suites, robots, trials, full})
        if (opt->count())
          throw InputError("", opt->get_name(), "is for the suites; scenario files are the trials themselves");
    if (o->full) {
      r.suites.clear();
      for (const auto& s : bench::allSuites())
        if (s.paper()) r.suites.push_back(s.name);
      r.robots.clear();
      // The paper's methods: lacam, the crowd solver, is none of them.
      r.methods.clear();
      for (const std::string& m : bench::allMethods())
        if (m != "lacam") r.methods.push_back(m);
      if (!trials->count()) r.trials = kFullTrials;
    }
    if (suites->count()) r.suites = expandCrowd(bench::splitOptionList(o->suites, "--suites"));
    // Crowd suites alone grow to their own counts (hundreds of robots).
    if (!robots->count() && std::all_of(r.suites.begin(), r.suites.end(), isCrowdSuite)) r.robots.clear();
    if (robots->count()) r.robots = parseCounts(o->robots);
    if (methods->count()) r.methods = bench::splitOptionList(o->methods, "--methods");
    r.method_args = parseMethodArgs(o->method_args);
    if (o->refine > 0)
      for (const std::string& m : r.methods) r.method_args[m].push_back("--refine=" + exactNumber(o->refine));
    if (r.suites.empty()) throw InputError("", "--suites", "no suite given");
    if (r.methods.empty()) throw InputError("", "--methods", "no method given");
    bench::RunSummary s = bench::runBenchmark(r, std::cout);
    cli::setExitCode(s.interrupted ? 130 : s.invalid ? 1 : 0);
  });
}

cli::Registrar registered_run("earc-bench", "run", setupRun);

}  // namespace
}  // namespace earc
