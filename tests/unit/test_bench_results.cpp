// The benchmark's results database: resumption keys, the queries a resumed
// run asks, what it refuses, and rows no run writes.
#include <doctest/doctest.h>


#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <iterator>
#include <optional>
#include <set>
#include <sstream>
#include <unistd.h>

#include "earc/bench/options.hpp"
#include "earc/bench/report.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/bench/suites.hpp"
#include "earc/cli/subcommands.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/gen/embedded_maps.hpp"
#include "earc/gen/movingai.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"

using namespace earc;
using namespace earc::bench;
#include "bench_results_fixtures.hpp"

using namespace earc::bench_test;

TEST_CASE("one read of the trials, at open, serves the queries a resumed run asks before it starts") {
  TempPath file("earc-results-one-read");
  TrialRecord args = trial("arc", 0, true, 1.0);
  args.planner_args = {"--window=4"};
  {
    ResultsDb db(file.path);
    CHECK(db.addTrial(args));
  }
  ResultsDb db(file.path);
  TrialRecord lightning = lightningTrial(0, perRobotLightning(4, 2.5));
  lightning.learn = false;
  {
    // Added by another process once this one has read the file: not in
    // what it read, which every query answers from, not read again.
    ResultsDb other(file.path);
    CHECK(other.addTrial(lightning));
  }
  CHECK(db.plannerArgs("arc") == args.planner_args);
  CHECK_FALSE(db.lightningSettings().has_value());
  CHECK_FALSE(db.learn("lightning").has_value());
  CHECK(db.recordedTrials().size() == 1);
  // trials() reads now, and the queries answer from that.
  CHECK(db.trials().size() == 2);
  CHECK(db.recordedTrials().size() == 2);
  CHECK(db.lightningSettings() == lightning.lightning);
  CHECK(db.learn("lightning") == false);
  // A trial added through it is in the next answers.
  CHECK(db.addTrial(earcTrial(0, true, "e.sqlite", 1)));
  CHECK(db.learn("earc") == true);
  CHECK(db.plannerArgs("earc") == std::vector<std::string>{});
  CHECK(db.recordedTrials().size() == 3);
}

TEST_CASE("a results file keeps one --learn per method: a trial run with the other is not added") {
  TempPath file("earc-results-learn-one");
  ResultsDb db(file.path);
  CHECK(db.addTrial(earcTrial(0, false, "e.sqlite", 1)));
  CHECK_THROWS_WITH_AS(db.addTrial(earcTrial(1, true, "e.sqlite", 1)),
                       (file.path + ": its earc trials ran with no --learn (fixed databases) (row id 1); a trial run "
                                    "with --learn is not added: a results file holds one --learn setting per method")
                           .c_str(),
                       InputError);
  // Per method: lightning's may learn; the same goes on.
  TrialRecord l = lightningTrial(0, perRobotLightning(4, 10));
  l.learn = true;
  CHECK(db.addTrial(l));
  CHECK(db.addTrial(earcTrial(1, false, "e.sqlite", 1)));
  CHECK(db.trials().size() == 3);
}

TEST_CASE("a results file keeps one set of planner arguments per method: a trial run with another is not added") {
  TempPath file("earc-results-args-per-method");
  ResultsDb db(file.path);
  TrialRecord with = trial("earc", 0, true, 1.0);
  with.planner_args = {"--db-k=5"};
  CHECK(db.addTrial(with));
  TrialRecord other = trial("earc", 1, true, 1.0);
  other.planner_args = {"--db-k=3"};
  TrialRecord none = trial("earc", 2, true, 1.0);
  CHECK_THROWS_WITH_AS(db.addTrial(other),
                       (file.path + ": its earc trials ran with [\"--db-k=5\"] (row id 1); a trial run with "
                                    "[\"--db-k=3\"] is not added: a results file holds one set per method")
                           .c_str(),
                       InputError);
  CHECK_THROWS_AS(db.addTrial(none), InputError);
  // Another method has its own; the same arguments go on.
  CHECK(db.addTrial(trial("arc", 0, true, 1.0)));
  TrialRecord same = trial("earc", 1, true, 1.0);
  same.planner_args = {"--db-k=5"};
  CHECK(db.addTrial(same));
  CHECK(db.trials().size() == 3);
}

TEST_CASE("a results database records a trial once per key and reports it as finished") {
  TempPath file("earc-results");
  {
    ResultsDb db(file.path);
    CHECK(db.addTrial(trial("arc", 0, true, 1.5)));
    CHECK_FALSE(db.addTrial(trial("arc", 0, false, 9.0)));  // same key: kept as it was
    CHECK(db.addTrial(trial("earc", 0, true, 1.0)));
  }
  ResultsDb db(file.path, true);
  const auto all = db.trials();
  REQUIRE(all.size() == 2);
  CHECK(all[0].success);
  CHECK(all[0].planning_time_s == doctest::Approx(1.5));
  CHECK(all[0].scenario_seed == 0xffffffffffffffffULL);  // 64-bit seeds survive
  CHECK(all[0].failure.empty());
  CHECK_FALSE(all[0].conflicts.has_value());  // NULL stays NULL
  const auto done = db.finishedTrials(1, 60);
  CHECK(done.count({"mobile", 4, "arc", 0}) == 1);
  CHECK(db.finishedTrials(2, 60).empty());   // another seed
  CHECK(db.finishedTrials(1, 30).empty());   // another time limit
}

TEST_CASE("a results database refuses files of other applications and newer schemas") {
  TempPath file("earc-results-foreign");
  std::ofstream(file.path) << "plain text, not SQLite at all, long enough to have a header of its own........";
  CHECK_THROWS_AS(ResultsDb(file.path), InputError);
}

TEST_CASE("a results database without a table of its schema is refused as damaged, whatever the reader") {
  for (const char* table : {"trials", "databases"}) {
    TempPath file(std::string("earc-results-no-") + table);
    { ResultsDb created(file.path); }
    {
      exp::Connection c(file.path, exp::OpenMode::ReadWrite);
      c.exec(std::string("DROP TABLE ") + table);
    }
    const std::string want =
        file.path + ": damaged database file (table " + table + " is missing; schema version " +
        std::to_string(kResultsSchemaVersion) + " has it)";
    for (bool read_only : {true, false}) CHECK_THROWS_WITH_AS(ResultsDb(file.path, read_only), want.c_str(), InputError);
  }
}

TEST_CASE("databases are recorded with their construction time, entries and size") {
  TempPath file("earc-results-dbs");
  ResultsDb db(file.path);
  DatabaseRecord d;
  d.method = "lightning";
  d.suite = "mobile";
  d.robots = 4;
  d.path = "/tmp/x.lightning";
  d.construction_time_s = 12.5;
  d.entries = 16;
  d.size_bytes = 4096;
  db.addDatabase(d);
  CHECK(db.hasDatabase("lightning", "/tmp/x.lightning"));
  CHECK_FALSE(db.hasDatabase("earc", "/tmp/x.lightning"));
  const auto all = db.databases();
  REQUIRE(all.size() == 1);
  CHECK(all[0].entries == 16);
  CHECK_FALSE(all[0].problems.has_value());
}

TEST_CASE("a results row with a value no run writes refuses the file, naming the row and the column") {
  TempPath file("earc-results-nonsense");
  {
    ResultsDb db(file.path);
    TrialRecord solved = trial("arc", 0, true, 1.5);
    solved.planning_time_s.reset();  // a solution need not report its time
    db.addTrial(solved);
    db.addTrial(trial("arc", 1, false, 60.5));  // a failed trial's time may pass its limit
    DatabaseRecord d;
    d.method = "earc";
    d.suite = "mobile";
    d.path = "/tmp/e.sqlite";
    db.addDatabase(d);
  }
  { CHECK(ResultsDb(file.path, true).trials().size() == 2); }
  struct Edit {
    const char* sql;
    const char* says;
  };
  const Edit edits[] = {
      {"UPDATE trials SET robots = -3 WHERE id = 2", "trials row id 2, column robots: -3 is not a robot count from 2 to 1024"},
      {"UPDATE trials SET robots = 2.5", "trials row id 1, column robots: 2.5 is not a robot count from 2 to 1024"},
      {"UPDATE trials SET planning_time_s = 'fast' WHERE id = 2",
       "trials row id 2, column planning_time_s: 'fast' is not a number of seconds (0 or more)"},
      {"UPDATE trials SET wall_time_s = -1e999", "trials row id 1, column wall_time_s: -inf is not a number of seconds (0 or more)"},
      {"UPDATE trials SET time_limit_s = 0", "trials row id 1, column time_limit_s: 0 is not a number of seconds above 0"},
      {"UPDATE trials SET suite = 'moon'", "trials row id 1, column suite: 'moon' is not a suite earc-bench runs (mobile, "},
      {"UPDATE trials SET method = x'00'", "trials row id 1, column method: a blob is not text"},
      {"UPDATE trials SET seed = '007'", "trials row id 1, column seed: '007' is not a seed"},
      {"UPDATE trials SET planner_seed = '18446744073709551616'", "trials row id 1, column planner_seed: '18446744073709551616' is not a seed"},
      {"UPDATE trials SET failure = 'oops' WHERE id = 1",
       "trials row id 1, column failure: 'oops' beside success 1: a solved trial has no failure"},
      {"UPDATE trials SET failure = NULL WHERE id = 2",
       "trials row id 2, column failure: NULL beside success 0: a failed trial says why it failed"},
      {"UPDATE trials SET planning_time_s = 61 WHERE id = 1",
       "trials row id 1, column planning_time_s: 61 s of a solved trial is beyond its time limit of 60 s"},
      {"UPDATE trials SET exit_status = 256", "trials row id 1, column exit_status: 256 is not an exit status from 0 to 255"},
      {"UPDATE trials SET finished_at = 'yesterday'",
       "trials row id 1, column finished_at: 'yesterday' is not a UTC time like 2026-11-24T01:02:03Z"},
      {"UPDATE trials SET jobs = 0", "trials row id 1, column jobs: 0 is not a number of jobs (1 or more)"},
      {"UPDATE trials SET bench_version = x'01'", "trials row id 1, column bench_version: a blob is not text"},
      {"UPDATE trials SET planner_args = '--window=4'",
       "trials row id 1, column planner_args: '--window=4' is not a JSON array of planner arguments (strings)"},
      {"UPDATE trials SET planner_args = '[]'",
       "trials row id 1, column planner_args: '[]' is not a JSON array of planner arguments (strings)"},
      {"UPDATE trials SET planner_args = '[\"--seed=3\"]'",
       "trials row id 1, column planner_args: '[\"--seed=3\"]' is not what a run gives a planner: '--seed=3' sets "
       "what earc-bench gives earc-plan itself"},
      // Both rows are arc's: two sets of arguments for one method.
      {"UPDATE trials SET planner_args = '[\"--window=4\"]' WHERE id = 2",
       "trials row id 2, column planner_args: '[\"--window=4\"]' beside NULL of method arc in row id 1: a results "
       "file holds one set of planner arguments per method"},
      {"UPDATE trials SET scenario_file = 'a.json' WHERE id = 1",
       "trials row id 1, column scenario_file: 'a.json' beside suite mobile: only a scenario file's trial (suite "
       "files) names a file"},
      {"UPDATE trials SET suite = 'files', scenario_file = '' WHERE id = 1",
       "trials row id 1, column scenario_file: '' is not a path"},
      {"UPDATE trials SET suite = 'files', scenario_file = x'01' WHERE id = 1",
       "trials row id 1, column scenario_file: a blob is not text"},
      {"UPDATE trials SET lightning_problems = 3 WHERE id = 1",
       "trials row id 1, column lightning_problems: 3 beside method arc: only a lightning trial records Lightning "
       "settings"},
      {"UPDATE trials SET method = 'lightning', lightning_problem_time_limit_s = 5 WHERE id = 1",
       "trials row id 1, column lightning_problems: NULL beside lightning_problems_per_robot NULL: a lightning trial "
       "records one of them"},
      {"UPDATE trials SET method = 'lightning', lightning_problems = 2, lightning_problems_per_robot = 4,"
       " lightning_problem_time_limit_s = 5 WHERE id = 1",
       "trials row id 1, column lightning_problems_per_robot: 4 beside lightning_problems 2: problems per robot are "
       "for a run without a number of problems"},
      {"UPDATE trials SET method = 'lightning', lightning_problems = 0, lightning_problem_time_limit_s = 5 WHERE id = 1",
       "trials row id 1, column lightning_problems: 0 is not a number of problems (1 or more)"},
      {"UPDATE trials SET method = 'lightning', lightning_problems_per_robot = 4 WHERE id = 1",
       "trials row id 1, column lightning_problem_time_limit_s: NULL is not a number of seconds above 0"},
      {"UPDATE trials SET method = 'lightning', lightning_problems_per_robot = 4, lightning_problem_time_limit_s = 5;"
       " UPDATE trials SET lightning_problem_time_limit_s = 2 WHERE id = 2",
       "trials row id 2, column lightning_problem_time_limit_s: 2 beside 5 in row id 1: a results file holds one "
       "Lightning setting"},
      {"UPDATE trials SET learn = 1 WHERE id = 1",
       "trials row id 1, column learn: 1 beside method arc: only a trial of a method with a database (earc, "
       "lightning) records --learn"},
      {"UPDATE trials SET method = 'earc', learn = 2 WHERE id = 1", "trials row id 1, column learn: 2 is not 0 or 1"},
      {"UPDATE trials SET method = 'earc', learn = 1; UPDATE trials SET learn = 0 WHERE id = 2",
       "trials row id 2, column learn: 0 beside 1 of method earc in row id 1: a results file holds one --learn "
       "setting per method"},
      {"UPDATE trials SET earc_db = 'e.sqlite' WHERE id = 1",
       "trials row id 1, column earc_db: 'e.sqlite' beside method arc: only an earc trial records an E-ARC database"},
      {"UPDATE trials SET method = 'earc', earc_db = '' WHERE id = 1", "trials row id 1, column earc_db: '' is not a path"},
      {"UPDATE trials SET method = 'earc', earc_db_state = 7 WHERE id = 1",
       "trials row id 1, column earc_db_state: 7 beside earc_db NULL: only a trial that records its E-ARC database "
       "records its state"},
      {"UPDATE trials SET method = 'earc', earc_db = 'e.sqlite', earc_db_state = 'x' WHERE id = 1",
       "trials row id 1, column earc_db_state: 'x' is not a history token (a whole number)"},
      {"UPDATE databases SET method = 'arc'", "databases row id 1, column method: 'arc' is not a method with a database (earc, lightning)"},
      {"UPDATE databases SET robots = 1",
       "databases row id 1, column robots: 1 is not 0 (every robot count) or a robot count from 2 to 1024"},
      {"UPDATE databases SET size_bytes = -1", "databases row id 1, column size_bytes: -1 is not a count (0 or more)"},
  };
  for (const Edit& e : edits) {
    CAPTURE(e.sql);
    TempPath copy("earc-results-nonsense-copy");
    std::filesystem::copy_file(file.path, copy.path);
    {
      exp::Connection c(copy.path, exp::OpenMode::ReadWrite);
      c.exec(e.sql);
    }
    const std::string want = copy.path + ": " + e.says;
    // Refused at open, by readers and writers alike.
    for (bool read_only : {true, false}) {
      CAPTURE(read_only);
      try {
        ResultsDb db(copy.path, read_only);
        FAIL("opened");
      } catch (const InputError& error) {
        CHECK_MESSAGE(std::string(error.what()).rfind(want, 0) == 0, error.what());
      }
    }
  }
}
