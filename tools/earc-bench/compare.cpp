// earc-bench compare: one earc-plan build (or set of options) against
// another, plan by plan on the same scenarios (see earc/bench/compare.hpp).
//
//   earc-bench compare --old PROGRAM [--new PROGRAM] [--old-arg A]... [--new-arg A]...
//     [SCENARIO.json...] [--suite S --robots N --trials T] [--method M] [--old-method M] [--new-method M] [--db FILE]
//     [--time-limit S] [--seed S] [--repeats R] [--csv FILE] [--picture FILE.svg|png]
//
// Exit status 0 when the comparison finished, 1 when some solution was
// INVALID, 2 for bad options or a side that refused the first plan's
// options or database, 130 when interrupted.
#include <iostream>

#include "earc/bench/compare.hpp"
#include "earc/cli/subcommands.hpp"
#include "earc/io/json_io.hpp"

namespace earc {
namespace {

void setupCompare(CLI::App& app) {
  auto o = std::make_shared<bench::CompareOptions>();
  auto* cmd = app.add_subcommand(
      "compare", "Compare two earc-plan builds or option sets plan by plan on the same scenarios: paired time ratio, "
                 "same paths");
  cmd->add_option("scenarios", o->scenarios, "Scenario files (default: generated from --suite, --robots, --trials)");
  cmd->add_option("--old", o->old_program, "The earc-plan taken as the reference")->required();
  cmd->add_option("--new", o->new_program, "The earc-plan measured against it (default: the one next to earc-bench)");
  cmd->add_option("--old-arg", o->old_args, "An argument added to the old side's plan command (repeatable; "
                                             "write --old-arg=--window --old-arg=20)");
  cmd->add_option("--new-arg", o->new_args, "An argument added to the new side's plan command (repeatable)");
  cmd->add_option("--suite", o->suite, "Suite of the generated scenarios")->capture_default_str();
  cmd->add_option("--robots", o->robots, "Robots of the generated scenarios")
      ->check(earc::cli::wholeNumberIn(2, 1000000))
      ->capture_default_str();
  cmd->add_option("--trials", o->trials, "Generated scenarios (the same as earc-bench run's trials for this seed)")
      ->check(earc::cli::kPositiveWholeNumber)
      ->capture_default_str();
  cmd->add_option("--method", o->method, "earc, arc, lightning, prioritized or coupled")->capture_default_str();
  cmd->add_option("--old-method", o->old_method, "The old side's method (default: --method), e.g. arc against earc");
  cmd->add_option("--new-method", o->new_method, "The new side's method (default: --method)");
  cmd->add_option("--db", o->db, "Database for earc or lightning, copied afresh for every plan");
  cmd->add_option("--time-limit", o->time_limit_s, "Planning time limit per plan, seconds")
      ->check(earc::cli::kFinitePositive)
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Seed: the generated scenarios, planner seeds, the bootstrap")
      ->check(earc::cli::kWholeNumber)
      ->capture_default_str();
  cmd->add_option("--repeats", o->repeats, "Plans per scenario and side; each side's median counts")
      ->check(earc::cli::kPositiveWholeNumber)
      ->capture_default_str();
  cmd->add_option("--work-dir", o->work_dir, "Scenarios, logs, database copies, failed plans' solutions")
      ->capture_default_str();
  cmd->add_option("--csv", o->csv, "Write one row per pair of plans");
  cmd->add_option("--picture", o->picture, "Draw new against old per scenario (.svg, or .png with rsvg-convert)");
  cmd->add_option("--memory-limit-mb", o->memory_limit_mb, "Address-space limit of each plan's process (MiB)")
      ->check(earc::cli::kPositiveWholeNumber)
      ->capture_default_str();
  cmd->add_flag("-v,--verbose", o->verbose, "One line per scenario");
  cmd->callback([o] {
    // With --csv /dev/stdout the report goes to stderr, not into the CSV.
    const bench::CompareSummary s = bench::runCompare(*o, summaryStream({o->csv, o->picture}));
    cli::setExitCode(s.interrupted ? 130 : s.stats.invalid ? 1 : 0);
  });
}

cli::Registrar registered_compare("earc-bench", "compare", setupCompare);

}  // namespace
}  // namespace earc
