// The migrations in migrations/results/*.sql, embedded in the binary.
//
// Kept by hand, byte for byte equal to the files: a unit test
// (test_bench_results_schema.cpp) compares each entry with its file. To add
// a migration: write migrations/results/NNNN_name.sql, paste it here as the
// next entry, raise kResultsSchemaVersion and read its columns
// (results_db.cpp, kAddedTrialColumns).
#include "earc/bench/results_migrations.hpp"

#include <iterator>

#include "earc/bench/results_db.hpp"

namespace earc::bench {

namespace {

constexpr ResultsMigration kResultsMigrations[] = {
    {1, "0001_trials_and_databases.sql", R"sql(-- Results migration 1: the trials and the databases they used.
-- trials: one row per planned trial. UNIQUE (suite, robots, method, trial,
-- seed, time_limit_s) is the key a resumed run skips on. Seeds are decimal
-- TEXT (64-bit unsigned). success is 1 only for a solution that
-- `earc-plan validate` accepted within the time limit; failure says why not
-- (NULL on success). planning_time_s is the planner's own figure
-- (stats.planning_time_s), NULL when the process died before reporting one.
-- databases: one row per database built for a run; robots = 0 for a
-- database that serves every robot count (E-ARC's).
-- (No comments inside the statements: SQLite keeps their text.)
CREATE TABLE trials (
  id INTEGER PRIMARY KEY,
  suite TEXT NOT NULL,
  robots INTEGER NOT NULL,
  method TEXT NOT NULL,
  trial INTEGER NOT NULL,
  seed TEXT NOT NULL,
  time_limit_s REAL NOT NULL,
  scenario_seed TEXT NOT NULL,
  planner_seed TEXT NOT NULL,
  success INTEGER NOT NULL CHECK (success IN (0, 1)),
  planning_time_s REAL,
  wall_time_s REAL NOT NULL,
  makespan INTEGER,
  sum_of_costs INTEGER,
  conflicts INTEGER,
  db_hits INTEGER,
  peak_memory_kb INTEGER,
  exit_status INTEGER,
  term_signal INTEGER,
  failure TEXT,
  finished_at TEXT NOT NULL,
  UNIQUE (suite, robots, method, trial, seed, time_limit_s)
);
CREATE TABLE databases (
  id INTEGER PRIMARY KEY,
  method TEXT NOT NULL,
  suite TEXT NOT NULL,
  robots INTEGER NOT NULL,
  path TEXT NOT NULL,
  construction_time_s REAL,
  entries INTEGER,
  size_bytes INTEGER,
  problems INTEGER,
  seed TEXT,
  recorded_at TEXT NOT NULL
);
)sql"},
    {2, "0002_jobs.sql", R"sql(-- Results migration 2: how many trials the run had at once (--jobs).
-- Side by side, trials disturb each other's timings, and how depends on the
-- order (see runner.cpp). NULL for trials recorded before it.
ALTER TABLE trials ADD COLUMN jobs INTEGER;
)sql"},
    {3, "0003_planner_version.sql", R"sql(-- Results migration 3: the build that planned the trial (the earc_version
-- its solution reported), so that every figure can be traced to its code.
-- NULL for trials recorded before it and for planners that do not say.
ALTER TABLE trials ADD COLUMN planner_version TEXT;
)sql"},
    {4, "0004_bench_version.sql", R"sql(-- Results migration 4: the earc-bench build that ran and timed the trial
-- (its --version). How trials are run changes their timings too, and
-- --plan-program plans with another build than the one timing. NULL for
-- trials recorded before it.
ALTER TABLE trials ADD COLUMN bench_version TEXT;
)sql"},
    {5, "0005_planner_args.sql", R"sql(-- Results migration 5: the arguments the run added to the trial's
-- `earc-plan plan` (--method-arg), as a JSON array of strings: E-ARC with
-- --db-k=5 is another experiment than E-ARC. NULL for none, as for every
-- trial recorded before it. All trials of one method in a file have the
-- same, so that table, export and plot never pool two settings in a cell.
ALTER TABLE trials ADD COLUMN planner_args TEXT;
)sql"},
    {6, "0006_scenario_file.sql", R"sql(-- Results migration 6: the path of a scenario file's trial (suite
-- kFilesSuite, earc-bench run FILE...) as the run was given it: its suite,
-- robot count and trial number say only where among the files it came.
-- NULL for a suite's trials, and for every trial recorded before it.
ALTER TABLE trials ADD COLUMN scenario_file TEXT;
)sql"},
    {7, "0007_lightning_settings.sql", R"sql(-- Results migration 7: how the run grew its Lightning databases
-- (--lightning-problems, else --lightning-problems-per-robot; and
-- --lightning-problem-time-limit), on each lightning trial: a database grown
-- from other problems or under another limit is another experiment, which a
-- resumed run must not pool with the first. NULL on other methods' trials
-- and on every trial recorded before it.
ALTER TABLE trials ADD COLUMN lightning_problems INTEGER;
ALTER TABLE trials ADD COLUMN lightning_problems_per_robot INTEGER;
ALTER TABLE trials ADD COLUMN lightning_problem_time_limit_s REAL;
)sql"},
    {8, "0008_learn_and_earc_db.sql", R"sql(-- Results migration 8: on each earc and lightning trial whether its run let
-- the databases learn (--learn, 1 or 0), and on each earc trial the E-ARC
-- database it used (as the run was given it or made it) and where that
-- database's history stood when the run began (the token of its last line,
-- NULL for a database without one): a resumed run on another database, or
-- with learning switched, must not pool its trials with the first. NULL
-- elsewhere and on every trial recorded before it.
ALTER TABLE trials ADD COLUMN learn INTEGER;
ALTER TABLE trials ADD COLUMN earc_db TEXT;
ALTER TABLE trials ADD COLUMN earc_db_state INTEGER;
)sql"},
    {9, "0009_lower_bound_and_refine.sql", R"sql(-- Results migration 9: what the crowd suites report beside the time: the
-- sum-of-costs lower bound of the trial's scenario (the sum of its robots'
-- own shortest paths in steps, bench/crowds.hpp), and the solution's
-- stats.refine (earc-plan --refine) when it has them, so that cost is
-- compared with the bound. NULL otherwise and on every trial recorded
-- before it.
ALTER TABLE trials ADD COLUMN lower_bound INTEGER;
ALTER TABLE trials ADD COLUMN refine_first_time_s REAL;
ALTER TABLE trials ADD COLUMN refine_first_sum_of_costs INTEGER;
ALTER TABLE trials ADD COLUMN refine_final_sum_of_costs INTEGER;
ALTER TABLE trials ADD COLUMN refine_final_makespan INTEGER;
)sql"},
};
static_assert(std::size(kResultsMigrations) == kResultsSchemaVersion, "a migration for every version");

}  // namespace

std::span<const ResultsMigration> resultsMigrations() { return kResultsMigrations; }

}  // namespace earc::bench
