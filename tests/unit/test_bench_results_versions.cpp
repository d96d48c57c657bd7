// The benchmark's results database across schema versions: each version's
// columns written, read from older files, and migrated.
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
#include "earc/experience/sqlite.hpp"
#include "earc/gen/embedded_maps.hpp"
#include "earc/gen/movingai.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/cli/subcommands.hpp"

using namespace earc;
using namespace earc::bench;
#include "bench_results_fixtures.hpp"

using namespace earc::bench_test;

TEST_CASE("a results database remembers how many trials ran at once, and reads and migrates version 1 files") {
  TempPath file("earc-results-jobs");
  {
    ResultsDb db(file.path);
    TrialRecord t = trial("arc", 0, true, 1.5);
    t.jobs = 2;
    CHECK(db.addTrial(t));
  }
  // Made a version 1 file, as an earlier earc-bench left it: no jobs
  // column (nor version 3's planner_version).
  makeOlder(file.path, 1);
  {
    // Read as it is: jobs unknown, the file still version 1.
    ResultsDb db(file.path, true);
    const auto all = db.trials();
    REQUIRE(all.size() == 1);
    CHECK_FALSE(all[0].jobs.has_value());
    CHECK(all[0].planning_time_s == doctest::Approx(1.5));
    CHECK(jobsNote(all) == "How many trials ran at once was not recorded for 1 trial (results from before schema version 2).");
  }
  {
    exp::Connection c(file.path, exp::OpenMode::ReadOnly);
    CHECK(c.pragmaInt("user_version") == 1);
  }
  {
    // Opened for writing: migrated, the old row kept, new rows with jobs.
    ResultsDb db(file.path);
    TrialRecord t = trial("earc", 0, true, 1.0);
    t.jobs = 1;
    CHECK(db.addTrial(t));
  }
  exp::Connection c(file.path, exp::OpenMode::ReadOnly);
  CHECK(c.pragmaInt("user_version") == kResultsSchemaVersion);
  ResultsDb db(file.path, true);
  const auto all = db.trials();
  REQUIRE(all.size() == 2);
  CHECK_FALSE(all[0].jobs.has_value());
  CHECK(all[1].jobs == 1);
  CHECK(jobsNote(all) == "Trials ran one at a time. How many trials ran at once was not recorded for 1 trial "
                         "(results from before schema version 2).");
  std::vector<TrialRecord> mixed = all;
  mixed[0].jobs = 2;
  CHECK(jobsNote(mixed) == "Trials ran with --jobs 1 (1), --jobs 2 (1): timings of different runs are not alike.");
  mixed[1].jobs = 2;
  CHECK(jobsNote(mixed).rfind("Trials ran 2 at a time (--jobs 2)", 0) == 0);
  CHECK(markdownTable(mixed, {}).find("Trials ran 2 at a time") != std::string::npos);
  CHECK(markdownWideTable(mixed).find("Trials ran 2 at a time") != std::string::npos);
}

TEST_CASE("a results database records which build planned each trial, and reads and migrates version 2 files") {
  TempPath file("earc-results-version");
  const auto all = checkBuildColumn(
      {&TrialRecord::planner_version, 3, versionNote, "Planned by earc 0.1.0+aaaaaaa.",
       "Which build planned was not recorded for 1 trial (results from before schema version 3, or a planner that "
       "does not say).",
       "Planned by 2 builds: earc 0.1.0+aaaaaaa (2 trials), earc 0.1.0+bbbbbbb.dirty (1 trial): their times are of "
       "different code."},
      file.path);
  CHECK(markdownWideTable(all).find("\nPlanned by 2 builds: ") != std::string::npos);
  CHECK(markdownTable(all, {}).find("\nPlanned by 2 builds: ") != std::string::npos);
  std::ostringstream csv;
  writeCsv(all, csv);
  CHECK(csv.str().find(",jobs,planner_version,") != std::string::npos);
  const auto rows = csvByColumn(csv.str());
  REQUIRE(rows.size() == 3);
  CHECK(rows[1].at("planner_version") == "0.1.0+bbbbbbb.dirty");
  CHECK(rows[1].at("bench_version").empty());
}

TEST_CASE("a results database records which earc-bench ran each trial, and reads and migrates version 3 files") {
  TempPath file("earc-results-bench");
  auto all = checkBuildColumn(
      {&TrialRecord::bench_version, 4, benchNote, "Timed by earc-bench 0.1.0+aaaaaaa.",
       "Which earc-bench timed was not recorded for 1 trial (results from before schema version 4).",
       "Timed by 2 builds: earc-bench 0.1.0+aaaaaaa (2 trials), earc-bench 0.1.0+bbbbbbb.dirty (1 trial): they "
       "were run and timed by different code."},
      file.path);
  // Under a table, after the planner's builds.
  for (auto& t : all) t.planner_version = "0.1.0+ccccccc";
  CHECK(trialsNotes(all).find("\nPlanned by earc 0.1.0+ccccccc.\nTimed by 2 builds: ") != std::string::npos);
  std::ostringstream csv;
  writeCsv(all, csv);
  CHECK(csv.str().find(",jobs,planner_version,bench_version,planner_args,scenario_file,") != std::string::npos);
  CHECK(csv.str().find(",0.1.0+ccccccc,0.1.0+bbbbbbb.dirty,,,") != std::string::npos);
}

TEST_CASE("a results database records each trial's planner arguments, and reads and migrates version 4 files") {
  TempPath file("earc-results-planner-args");
  const std::vector<std::string> k5 = {"--db-k=5", "--window", "4"};
  {
    ResultsDb db(file.path);
    TrialRecord t = trial("earc", 0, true, 1.0);
    t.planner_args = k5;
    CHECK(db.addTrial(t));
    CHECK(db.addTrial(trial("arc", 0, true, 1.5)));
    CHECK(db.plannerArgs("earc") == k5);
    CHECK(db.plannerArgs("arc") == std::vector<std::string>{});
    CHECK_FALSE(db.plannerArgs("lightning").has_value());
  }
  {
    // As stored: a JSON array; NULL for none.
    exp::Connection c(file.path, exp::OpenMode::ReadOnly);
    exp::Statement s = c.prepare("SELECT method, planner_args FROM trials ORDER BY id");
    REQUIRE(s.step());
    CHECK(s.textAt(1) == R"(["--db-k=5","--window","4"])");
    REQUIRE(s.step());
    CHECK(s.columnType(1) == SQLITE_NULL);
  }
  // A version 4 file, as an earlier earc-bench left it: read as it is,
  // every trial without arguments (none could be given then); migrated
  // when opened for writing, the old rows kept (with none).
  TrialRecord next = trial("prioritized", 0, true, 2.0);
  next.planner_args = {"--window=8"};
  const auto all =
      readOldThenMigrate(file.path, 4, [](const TrialRecord& t) { CHECK(t.planner_args.empty()); }, next);
  REQUIRE(all.size() == 3);
  CHECK(all[0].planner_args.empty());
  CHECK(all[1].planner_args.empty());
  CHECK(all[2].planner_args == std::vector<std::string>{"--window=8"});
}

TEST_CASE("a results database records a scenario file trial's file, and reads and migrates version 5 files") {
  TempPath file("earc-results-scenario-file");
  TrialRecord from_file = trial("arc", 0, true, 1.0, kFilesSuite, 3);
  from_file.scenario_file = "cell/a, b.json";
  {
    ResultsDb db(file.path);
    CHECK(db.addTrial(from_file));
    CHECK(db.addTrial(trial("arc", 0, true, 1.5)));  // a suite's: no file
    const auto all = db.trials();
    REQUIRE(all.size() == 2);
    CHECK(all[0].scenario_file == "cell/a, b.json");
    CHECK(all[1].scenario_file.empty());
    // The CSV's column after planner_args: the path as given (quoted as
    // needed), empty for a suite's trial.
    std::ostringstream csv;
    writeCsv(all, csv);
    CHECK(csv.str().find(",planner_args,scenario_file,") != std::string::npos);
    CHECK(csv.str().find(",,\"cell/a, b.json\",") != std::string::npos);
    const auto rows = csvByColumn(csv.str());
    REQUIRE(rows.size() == 2);
    CHECK(rows[0].at("suite") == "files");
    CHECK(rows[0].at("scenario_file") == "cell/a, b.json");
    CHECK(rows[1].at("scenario_file").empty());
  }
  {
    // As stored: the path; NULL for none.
    exp::Connection c(file.path, exp::OpenMode::ReadOnly);
    exp::Statement s = c.prepare("SELECT scenario_file FROM trials ORDER BY id");
    REQUIRE(s.step());
    CHECK(s.textAt(0) == "cell/a, b.json");
    REQUIRE(s.step());
    CHECK(s.columnType(0) == SQLITE_NULL);
  }
  // A version 5 file, as an earlier earc-bench left it: read as it is,
  // its files' trials without their file; migrated when opened for
  // writing, the old rows kept (without a file).
  TrialRecord next = from_file;
  next.trial = 1;
  next.scenario_file = "cell/c.json";
  const auto all =
      readOldThenMigrate(file.path, 5, [](const TrialRecord& t) { CHECK(t.scenario_file.empty()); }, next);
  REQUIRE(all.size() == 3);
  CHECK(all[0].scenario_file.empty());
  CHECK(all[1].scenario_file.empty());
  CHECK(all[2].scenario_file == "cell/c.json");
}

TEST_CASE("a plan command gives earc-plan its time limit exactly, however small or long") {
  PlanCommand c;
  c.program = "earc-plan";
  c.scenario = "s.json";
  c.solution = "o.json";
  c.method = "arc";
  const std::vector<std::pair<double, std::string>> limits = {{1e-7, "1e-07"}, {1.0000001, "1.0000001"}, {60.0, "60"}};
  for (const auto& [limit, text] : limits) {
    c.time_limit_s = limit;
    const std::vector<std::string> argv = planArgv(c);
    const auto at = std::find(argv.begin(), argv.end(), "--time-limit");
    REQUIRE(at + 1 < argv.end());
    CHECK(at[1] == text);
  }
}

TEST_CASE("a results database records each lightning trial's Lightning settings, and reads and migrates version 6 files") {
  TempPath file("earc-results-lightning");
  {
    ResultsDb db(file.path);
    CHECK_FALSE(db.lightningSettings().has_value());
    CHECK(db.addTrial(trial("arc", 0, true, 1.5)));
    CHECK_FALSE(db.lightningSettings().has_value());  // none of another method's
    CHECK(db.addTrial(lightningTrial(0, perRobotLightning(4, 10))));
    CHECK(db.lightningSettings() == perRobotLightning(4, 10));
    const auto all = db.trials();
    REQUIRE(all.size() == 2);
    CHECK_FALSE(all[0].lightning.has_value());
    CHECK(all[1].lightning == perRobotLightning(4, 10));
  }
  {
    // As stored: one count, the time; NULL on another method's trial.
    exp::Connection c(file.path, exp::OpenMode::ReadOnly);
    exp::Statement s = c.prepare(
        "SELECT lightning_problems, lightning_problems_per_robot, lightning_problem_time_limit_s FROM trials ORDER BY id");
    REQUIRE(s.step());
    for (int col : {0, 1, 2}) CHECK(s.columnType(col) == SQLITE_NULL);
    REQUIRE(s.step());
    CHECK(s.columnType(0) == SQLITE_NULL);
    CHECK(s.int64At(1) == 4);
    CHECK(s.doubleAt(2) == 10.0);
  }
  // A version 6 file, as an earlier earc-bench left it: read as it is,
  // no trial with settings; migrated when opened for writing, and a
  // lightning trial of any settings added beside the old ones, which
  // hold it to nothing.
  bench::LightningSettings twenty;
  twenty.problems = 20;
  twenty.problem_time_limit_s = 2.5;
  const auto all = readOldThenMigrate(
      file.path, 6, [](const TrialRecord& t) { CHECK_FALSE(t.lightning.has_value()); }, lightningTrial(1, twenty));
  REQUIRE(all.size() == 3);
  CHECK_FALSE(all[1].lightning.has_value());
  CHECK(all[2].lightning == twenty);
  CHECK(ResultsDb(file.path, true).lightningSettings() == twenty);
}

TEST_CASE("Lightning settings differ in the first option that says so, each value as a run gives it") {
  bench::LightningSettings twenty;
  twenty.problems = 20;
  twenty.problem_time_limit_s = 10;
  const auto says = [](const bench::LightningSettings& a, const bench::LightningSettings& b) {
    const auto d = lightningSettingDifference(a, b);
    return d ? d->option + ": " + d->stored + " / " + d->given : std::string("same");
  };
  CHECK(says(perRobotLightning(4, 10), perRobotLightning(4, 10)) == "same");
  CHECK(says(perRobotLightning(4, 10), perRobotLightning(2, 10)) == "--lightning-problems-per-robot: 4 / 2");
  CHECK(says(perRobotLightning(4, 10), perRobotLightning(4, 2.5)) == "--lightning-problem-time-limit: 10 / 2.5");
  // The shortest text that reads back as each: as the run was given it.
  CHECK(says(perRobotLightning(4, 1.0000001), perRobotLightning(4, 1.0000002)) ==
        "--lightning-problem-time-limit: 1.0000001 / 1.0000002");
  CHECK(says(perRobotLightning(4, 1.2345678), perRobotLightning(4, 2)) ==
        "--lightning-problem-time-limit: 1.2345678 / 2");
  CHECK(says(perRobotLightning(4, 1e-7), perRobotLightning(4, 0.1)) == "--lightning-problem-time-limit: 1e-07 / 0.1");
  CHECK(says(perRobotLightning(4, 10), twenty) == "--lightning-problems: none (4 per robot) / 20");
  CHECK(says(twenty, perRobotLightning(4, 10)) == "--lightning-problems: 20 / none (4 per robot)");
  bench::LightningSettings eight = twenty;
  eight.problems = 8;
  CHECK(says(twenty, eight) == "--lightning-problems: 20 / 8");
  eight.problems = 20;
  eight.problem_time_limit_s = 1;
  CHECK(says(twenty, eight) == "--lightning-problem-time-limit: 10 / 1");
}

TEST_CASE("a results file keeps one Lightning setting: a lightning trial run with another is not added") {
  TempPath file("earc-results-lightning-one");
  ResultsDb db(file.path);
  CHECK(db.addTrial(lightningTrial(0, perRobotLightning(4, 10))));
  CHECK_THROWS_WITH_AS(db.addTrial(lightningTrial(1, perRobotLightning(4, 2))),
                       (file.path + ": its lightning trials ran with --lightning-problem-time-limit 10 (row id 1); "
                                    "a trial run with 2 is not added: a results file holds one Lightning setting")
                           .c_str(),
                       InputError);
  bench::LightningSettings twenty;
  twenty.problems = 20;
  twenty.problem_time_limit_s = 10;
  CHECK_THROWS_AS(db.addTrial(lightningTrial(1, twenty)), InputError);
  // Other methods hold none; the same settings go on.
  CHECK(db.addTrial(trial("arc", 1, true, 1.0)));
  CHECK(db.addTrial(lightningTrial(1, perRobotLightning(4, 10))));
  CHECK(db.trials().size() == 3);
}

TEST_CASE("a results database records --learn and the E-ARC database of each trial, and reads and migrates version 7 files") {
  TempPath file("earc-results-learn");
  {
    ResultsDb db(file.path);
    CHECK_FALSE(db.learn("earc").has_value());
    CHECK(db.addTrial(trial("arc", 0, true, 1.5)));
    CHECK(db.addTrial(earcTrial(0, false, "w/earc-mobile.sqlite", -5)));
    TrialRecord l = lightningTrial(0, perRobotLightning(4, 10));
    l.learn = true;
    CHECK(db.addTrial(l));
    CHECK(db.learn("earc") == false);
    CHECK(db.learn("lightning") == true);
    CHECK_FALSE(db.learn("arc").has_value());
    const auto all = db.trials();
    REQUIRE(all.size() == 3);
    CHECK_FALSE(all[0].learn.has_value());
    CHECK(all[0].earc_db.empty());
    CHECK_FALSE(all[0].earc_db_state.has_value());
    CHECK(all[1].learn == false);
    CHECK(all[1].earc_db == "w/earc-mobile.sqlite");
    CHECK(all[1].earc_db_state == -5);
    CHECK(all[2].learn == true);
  }
  {
    // As stored: 0 or 1, the path, the token; NULL on another method's trial.
    exp::Connection c(file.path, exp::OpenMode::ReadOnly);
    exp::Statement s = c.prepare("SELECT learn, earc_db, earc_db_state FROM trials ORDER BY id");
    REQUIRE(s.step());
    for (int col : {0, 1, 2}) CHECK(s.columnType(col) == SQLITE_NULL);
    REQUIRE(s.step());
    CHECK(s.int64At(0) == 0);
    CHECK(s.textAt(1) == "w/earc-mobile.sqlite");
    CHECK(s.int64At(2) == -5);
    REQUIRE(s.step());
    CHECK(s.int64At(0) == 1);
    CHECK(s.columnType(1) == SQLITE_NULL);
  }
  // A version 7 file: read as it is, nothing recorded; migrated when
  // opened for writing, and an earc trial of either --learn added beside
  // the old ones, which hold it to nothing. A database without a history
  // leaves the state unset.
  const auto all = readOldThenMigrate(
      file.path, 7,
      [](const TrialRecord& t) {
        CHECK_FALSE(t.learn.has_value());
        CHECK(t.earc_db.empty());
        CHECK_FALSE(t.earc_db_state.has_value());
      },
      earcTrial(1, true, "e.sqlite", std::nullopt));
  REQUIRE(all.size() == 4);
  CHECK_FALSE(all[1].learn.has_value());
  CHECK(all[3].learn == true);
  CHECK(all[3].earc_db == "e.sqlite");
  CHECK_FALSE(all[3].earc_db_state.has_value());
  CHECK(ResultsDb(file.path, true).learn("earc") == true);
}

TEST_CASE("the CSV has the Lightning settings, --learn and the E-ARC database after the older columns") {
  TrialRecord earc = earcTrial(0, false, "w/e, mobile.sqlite", -5);
  TrialRecord lightning = lightningTrial(0, perRobotLightning(4, 2.5));
  lightning.learn = true;
  bench::LightningSettings twenty;
  twenty.problems = 20;
  twenty.problem_time_limit_s = 1.0000001;
  const std::vector<TrialRecord> all = {trial("arc", 0, true, 1.5), earc, lightning, lightningTrial(1, twenty),
                                        earcTrial(1, true, "e.sqlite", std::nullopt)};
  std::ostringstream csv;
  writeCsv(all, csv);
  // Schema 7's and 8's columns last, in their order: a script that read
  // the columns up to scenario_file by position reads them still.
  const std::string header = csv.str().substr(0, csv.str().find('\n'));
  CHECK(header ==
        "suite,robots,method,trial,seed,time_limit_s,scenario_seed,planner_seed,success,planning_time_s,"
        "wall_time_s,makespan,sum_of_costs,conflicts,db_hits,peak_memory_kb,exit_status,term_signal,failure,"
        "finished_at,jobs,planner_version,bench_version,planner_args,scenario_file,lightning_problems,"
        "lightning_problems_per_robot,lightning_problem_time_limit_s,learn,earc_db,earc_db_state,lower_bound,"
        "refine_first_time_s,refine_first_sum_of_costs,refine_final_sum_of_costs,refine_final_makespan");
  const auto rows = csvByColumn(csv.str());
  REQUIRE(rows.size() == 5);
  const auto fields = [&](std::size_t r) {
    const auto& row = rows[r];
    return row.at("lightning_problems") + "|" + row.at("lightning_problems_per_robot") + "|" +
           row.at("lightning_problem_time_limit_s") + "|" + row.at("learn") + "|" + row.at("earc_db") + "|" +
           row.at("earc_db_state");
  };
  CHECK(fields(0) == "|||||");  // another method's trial records none
  CHECK(fields(1) == "|||0|w/e, mobile.sqlite|-5");
  CHECK(fields(2) == "|4|2.5|1||");
  CHECK(fields(3) == "20||1.0000001|||");  // recorded before schema 8: no --learn
  CHECK(fields(4) == "|||1|e.sqlite|");    // a database without a history
  CHECK(csv.str().find(",\"w/e, mobile.sqlite\",-5,,,,,\n") != std::string::npos);
}
