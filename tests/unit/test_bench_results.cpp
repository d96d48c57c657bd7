// The benchmark's results database and its reports: schema and resumption
// keys, statistics, pairing by seed, CSV and OMPL benchmark logs.
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

namespace {

struct TempPath {
  std::string path;
  explicit TempPath(const std::string& name)
      : path((std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()))).string()) {
    std::filesystem::remove_all(path);
  }
  ~TempPath() {
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove_all(path + suffix);
  }
};

TrialRecord trial(const std::string& method, int t, bool ok, double secs, const std::string& suite = "mobile",
                  int robots = 4) {
  TrialRecord r;
  r.suite = suite;
  r.robots = robots;
  r.method = method;
  r.trial = t;
  r.seed = 1;
  r.time_limit_s = 60;
  r.scenario_seed = 0xffffffffffffffffULL - static_cast<std::uint64_t>(t);
  r.planner_seed = 42;
  r.success = ok;
  r.planning_time_s = secs;
  r.wall_time_s = secs + 0.1;
  if (ok) {
    r.makespan = 100;
    r.sum_of_costs = 300;
  } else {
    r.failure = "not solved: time_limit";
  }
  r.peak_memory_kb = 20480;
  r.exit_status = ok ? 0 : 1;
  return r;
}

// The lines of a text file.
std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// writeCsv's text as rows of (column name, field), the header's names,
// the fields unquoted (RFC 4180: "" in quotes is "); every row as wide as
// the header.
std::vector<std::map<std::string, std::string>> csvByColumn(const std::string& text) {
  std::vector<std::vector<std::string>> rows(1, std::vector<std::string>(1));
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted && c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
      rows.back().back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (!quoted && c == ',') {
      rows.back().emplace_back();
    } else if (!quoted && c == '\n') {
      rows.emplace_back(1);
    } else {
      rows.back().back() += c;
    }
  }
  if (rows.back() == std::vector<std::string>(1)) rows.pop_back();  // after the last line's end
  std::vector<std::map<std::string, std::string>> out;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    REQUIRE(rows[r].size() == rows[0].size());
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < rows[0].size(); ++c) row[rows[0][c]] = rows[r][c];
    out.push_back(row);
  }
  return out;
}

// Turns a results file into one an earlier earc-bench left at `version`:
// the columns later versions added are dropped, user_version set.
void makeOlder(const std::string& path, int version) {
  exp::Connection c(path, exp::OpenMode::ReadWrite);
  if (version < 9)
    c.exec("ALTER TABLE trials DROP COLUMN lower_bound; ALTER TABLE trials DROP COLUMN refine_first_time_s; ALTER "
           "TABLE trials DROP COLUMN refine_first_sum_of_costs; ALTER TABLE trials DROP COLUMN "
           "refine_final_sum_of_costs; ALTER TABLE trials DROP COLUMN refine_final_makespan");
  if (version < 8)
    c.exec("ALTER TABLE trials DROP COLUMN learn; ALTER TABLE trials DROP COLUMN earc_db; ALTER TABLE trials DROP "
           "COLUMN earc_db_state");
  if (version < 7)
    c.exec("ALTER TABLE trials DROP COLUMN lightning_problems; ALTER TABLE trials DROP COLUMN "
           "lightning_problems_per_robot; ALTER TABLE trials DROP COLUMN lightning_problem_time_limit_s");
  if (version < 6) c.exec("ALTER TABLE trials DROP COLUMN scenario_file");
  if (version < 5) c.exec("ALTER TABLE trials DROP COLUMN planner_args");
  if (version < 4) c.exec("ALTER TABLE trials DROP COLUMN bench_version");
  if (version < 3) c.exec("ALTER TABLE trials DROP COLUMN planner_version");
  if (version < 2) c.exec("ALTER TABLE trials DROP COLUMN jobs");
  c.exec("PRAGMA user_version = " + std::to_string(version));
}

// Makes the file one an earlier earc-bench left at `version`; checks that
// a reader takes it as it is (each trial through `check_old`) and leaves
// it at that version; adds `next` through a writer, which migrates it;
// returns every trial then read back.
std::vector<TrialRecord> readOldThenMigrate(const std::string& path, int version,
                                            const std::function<void(const TrialRecord&)>& check_old,
                                            const TrialRecord& next) {
  makeOlder(path, version);
  {
    ResultsDb db(path, true);
    for (const TrialRecord& t : db.trials()) check_old(t);
    exp::Connection c(path, exp::OpenMode::ReadOnly);
    CHECK(c.pragmaInt("user_version") == version);
  }
  {
    ResultsDb db(path);
    CHECK(db.addTrial(next));
  }
  exp::Connection c(path, exp::OpenMode::ReadOnly);
  CHECK(c.pragmaInt("user_version") == kResultsSchemaVersion);
  return ResultsDb(path, true).trials();
}

}  // namespace

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

namespace {

// A build column that schema version `since` added: written and read
// back; not there in a file made one version older, which is read as it
// is; there again once a write migrates the file, the old row kept.
// `note` says it under tables: of one build (A), of a trial that did not
// record it, and of two (A twice, B once). Returns the last trials read.
struct BuildColumn {
  std::string TrialRecord::*field;
  int since;
  std::string (*note)(const std::vector<TrialRecord>&);
  std::string one, unknown, two;
};

std::vector<TrialRecord> checkBuildColumn(const BuildColumn& col, const std::string& path) {
  const std::string a = "0.1.0+aaaaaaa", b = "0.1.0+bbbbbbb.dirty";
  {
    ResultsDb db(path);
    TrialRecord t = trial("arc", 0, true, 1.5);
    t.jobs = 1;
    t.*col.field = a;
    CHECK(db.addTrial(t));
  }
  {
    ResultsDb db(path, true);
    const auto all = db.trials();
    REQUIRE(all.size() == 1);
    CHECK(all[0].*col.field == a);
    CHECK(col.note(all) == col.one);
  }
  makeOlder(path, col.since - 1);
  {
    ResultsDb db(path, true);
    const auto all = db.trials();
    REQUIRE(all.size() == 1);
    CHECK((all[0].*col.field).empty());
    CHECK(all[0].jobs == 1);
    CHECK(col.note(all) == col.unknown);
    exp::Connection c(path, exp::OpenMode::ReadOnly);
    CHECK(c.pragmaInt("user_version") == col.since - 1);
  }
  {
    ResultsDb db(path);
    TrialRecord t = trial("earc", 0, true, 1.0);
    t.*col.field = b;
    CHECK(db.addTrial(t));
  }
  exp::Connection c(path, exp::OpenMode::ReadOnly);
  CHECK(c.pragmaInt("user_version") == kResultsSchemaVersion);
  ResultsDb db(path, true);
  auto all = db.trials();
  REQUIRE(all.size() == 2);
  CHECK((all[0].*col.field).empty());
  CHECK(all[1].*col.field == b);
  all[0].*col.field = a;
  all.push_back(all[0]);
  CHECK(col.note(all) == col.two);
  return all;
}

}  // namespace

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

namespace {

LightningSettings perRobotLightning(int per_robot, double time_limit_s) {
  LightningSettings l;
  l.problems_per_robot = per_robot;
  l.problem_time_limit_s = time_limit_s;
  return l;
}

TrialRecord lightningTrial(int t, const LightningSettings& settings) {
  TrialRecord r = trial("lightning", t, true, 1.0);
  r.lightning = settings;
  return r;
}

}  // namespace

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
  LightningSettings twenty;
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
  LightningSettings twenty;
  twenty.problems = 20;
  twenty.problem_time_limit_s = 10;
  const auto says = [](const LightningSettings& a, const LightningSettings& b) {
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
  LightningSettings eight = twenty;
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
  LightningSettings twenty;
  twenty.problems = 20;
  twenty.problem_time_limit_s = 10;
  CHECK_THROWS_AS(db.addTrial(lightningTrial(1, twenty)), InputError);
  // Other methods hold none; the same settings go on.
  CHECK(db.addTrial(trial("arc", 1, true, 1.0)));
  CHECK(db.addTrial(lightningTrial(1, perRobotLightning(4, 10))));
  CHECK(db.trials().size() == 3);
}

namespace {

TrialRecord earcTrial(int t, bool learn, const std::string& db, std::optional<std::int64_t> state) {
  TrialRecord r = trial("earc", t, true, 1.0);
  r.learn = learn;
  r.earc_db = db;
  r.earc_db_state = state;
  return r;
}

}  // namespace

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
  LightningSettings twenty;
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

TEST_CASE("quantiles interpolate between order statistics like numpy") {
  CHECK_FALSE(quantile({}, 0.5).has_value());
  CHECK(*quantile({3, 1, 2}, 0.5) == doctest::Approx(2));
  CHECK(*quantile({1, 2, 3, 4}, 0.5) == doctest::Approx(2.5));
  CHECK(*quantile({1, 2, 3, 4}, 0.25) == doctest::Approx(1.75));
  CHECK(*quantile({7}, 0.75) == doctest::Approx(7));
}

TEST_CASE("cells count every trial but time only the solved ones") {
  std::vector<TrialRecord> t = {trial("arc", 0, true, 1), trial("arc", 1, true, 3), trial("arc", 2, false, 60)};
  const auto cells = summarize(t);
  REQUIRE(cells.size() == 1);
  CHECK(cells[0].trials == 3);
  CHECK(cells[0].solved == 2);
  CHECK(*cells[0].median_s == doctest::Approx(2));
}

TEST_CASE("the table gives times with three significant digits, also below a millisecond") {
  // Medians of one trial each: a sub-millisecond plan read "0.000".
  const std::string md = markdownTable({trial("arc", 0, true, 0.000123), trial("earc", 0, true, 0.0456),
                                        trial("prioritized", 0, true, 0.5), trial("coupled", 0, true, 12.34)},
                                       {});
  CHECK(md.find("| 0.000123 |") != std::string::npos);
  CHECK(md.find("| 0.0456 |") != std::string::npos);
  CHECK(md.find("| 0.500 |") != std::string::npos);
  CHECK(md.find("| 12.3 |") != std::string::npos);
  CHECK(md.find("0.000 ") == std::string::npos);
}

TEST_CASE("the E-ARC/ARC ratio pairs trials by scenario and skips unpaired ones") {
  std::vector<TrialRecord> t = {trial("arc", 0, true, 2), trial("earc", 0, true, 1),   // 0.5
                                trial("arc", 1, true, 4), trial("earc", 1, true, 3),   // 0.75
                                trial("arc", 2, true, 4), trial("earc", 2, false, 60),  // unpaired
                                trial("earc", 3, true, 1)};
  PairedRatio r = pairedRatio(t, "mobile", 4, "earc", "arc");
  CHECK(r.pairs == 2);
  CHECK(*r.median == doctest::Approx(0.625));
  CHECK(*r.of_medians == doctest::Approx(2.0 / 3.0));  // medians of the paired trials: 2 and 3
  const std::string md = markdownTable(t, {});
  CHECK(md.find("### mobile") != std::string::npos);
  CHECK(md.find("| 4 | earc | 3/4 (75%) |") != std::string::npos);
  // Resampling two pairs gives ratios 0.5 or 0.75 alike: the interval
  // spans both, whichever statistic.
  REQUIRE(r.median_interval);
  CHECK(r.median_interval->first == doctest::Approx(0.5));
  CHECK(r.median_interval->second == doctest::Approx(0.75));
  CHECK(r.of_medians_interval->first == doctest::Approx(0.5));
  CHECK(r.of_medians_interval->second == doctest::Approx(0.75));
  CHECK(md.find("| mobile | 4 | 2 | 0.667 [0.500, 0.750] | 0.625 [0.500, 0.750] | 100 / 100 |") != std::string::npos);
  // Makespans on the same pairs only: E-ARC's unpaired trial 3 does not
  // count; none known, none shown.
  t[0].makespan = 100;
  t[1].makespan = 110;
  t[2].makespan = 200;
  t[3].makespan = 130;
  t[6].makespan = 999;
  r = pairedRatio(t, "mobile", 4, "earc", "arc");
  CHECK(*r.makespan_a == doctest::Approx(120));
  CHECK(*r.makespan_b == doctest::Approx(150));
  CHECK(markdownTable(t, {}).find("| 0.625 [0.500, 0.750] | 120 / 150 |") != std::string::npos);
  for (TrialRecord& x : t) x.makespan.reset();
  CHECK_FALSE(pairedRatio(t, "mobile", 4, "earc", "arc").makespan_a);
  CHECK(markdownTable(t, {}).find("| 0.625 [0.500, 0.750] | - |") != std::string::npos);
}

TEST_CASE("the wide table has a row per robot count, a column per method, the paired ratio and the hit rate") {
  std::vector<TrialRecord> t = {trial("arc", 0, true, 2), trial("earc", 0, true, 1),  // 0.5
                                trial("arc", 1, true, 4), trial("earc", 1, true, 3),  // 0.75
                                trial("coupled", 0, false, 60), trial("arc", 0, true, 8, "mobile", 8)};
  t[1].db_hits = 3;
  t[1].conflicts = 4;
  t[3].db_hits = 1;
  t[3].conflicts = 4;
  const std::string md = markdownWideTable(t);
  CHECK(md.find("| robots | earc | arc | coupled | E-ARC / ARC medians [95%] | E-ARC / ARC paired [95%] | E-ARC hit rate |") !=
        std::string::npos);
  CHECK(md.find("| 4 | 2/2 2.00 | 2/2 3.00 | 0/1 | 0.67 [0.50, 0.75] | 0.62 [0.50, 0.75] | 50% |") != std::string::npos);
  // E-ARC and coupled did not run at 8 robots.
  CHECK(md.find("| 8 | - | 1/1 8.00 | - | - | - | - |") != std::string::npos);
}

TEST_CASE("trials under different time limits are kept apart, each limit named where a suite has several") {
  // Two runs of one cell into one file, at 20 s and at 10 s: what the
  // 10 s run left unsolved the 20 s run solved, so one cell of both
  // would be neither experiment's.
  std::vector<TrialRecord> t = {trial("arc", 0, true, 2),  trial("earc", 0, true, 1),   // 20 s
                                trial("arc", 1, true, 4),  trial("earc", 1, true, 3),   // 20 s
                                trial("arc", 0, false, 10), trial("earc", 0, true, 5),  // 10 s
                                trial("arc", 0, true, 7, "arms", 2)};                    // 60 s, one limit
  for (std::size_t i = 0; i < 4; ++i) t[i].time_limit_s = 20;
  t[4].time_limit_s = t[5].time_limit_s = 10;
  const auto cells = summarize(t);
  REQUIRE(cells.size() == 5);
  CHECK(cells[0].method == "earc");
  CHECK(cells[0].time_limit_s == 10);
  CHECK(cells[2].time_limit_s == 20);
  CHECK(cells[3].trials == 2);

  const std::string md = markdownTable(t, {});
  const auto at10 = md.find("### mobile, time limit 10 s\n"), at20 = md.find("### mobile, time limit 20 s\n");
  REQUIRE(at10 != std::string::npos);
  REQUIRE(at20 != std::string::npos);
  CHECK(at10 < at20);
  CHECK(md.find("| 4 | arc | 0/1 (0%) | - | - |", at10) < at20);
  CHECK(md.find("| 4 | arc | 2/2 (100%) | 3.00 | 2.50 - 3.50 |", at20) != std::string::npos);
  CHECK(md.find("### mobile\n") == std::string::npos);
  CHECK(md.find("### arms\n") != std::string::npos);  // one limit: no need to name it
  // Paired within one limit: the 10 s run has no pair, the 20 s run two.
  CHECK(md.find("| mobile, time limit 10 s | 4 |") == std::string::npos);
  CHECK(md.find("| mobile, time limit 20 s | 4 | 2 | 0.667 [0.500, 0.750] |") != std::string::npos);
  CHECK(pairedRatio(t, "mobile", 4, "earc", "arc", 20.0).pairs == 2);
  CHECK(pairedRatio(t, "mobile", 4, "earc", "arc", 10.0).pairs == 0);

  t[5].db_hits = 1;
  t[5].conflicts = 1;
  const std::string wide = markdownWideTable(t);
  const auto w10 = wide.find("### mobile, time limit 10 s\n"), w20 = wide.find("### mobile, time limit 20 s\n");
  REQUIRE(w10 != std::string::npos);
  REQUIRE(w20 != std::string::npos);
  CHECK(wide.find("| 4 | 1/1 5.00 | 0/1 | - | - | 100% |", w10) < w20);
  CHECK(wide.find("| 4 | 2/2 2.00 | 2/2 3.00 | 0.67 [0.50, 0.75] | 0.62 [0.50, 0.75] | - |", w20) != std::string::npos);
  CHECK(wide.find("### arms\n") != std::string::npos);
}

TEST_CASE("CSV has one quoted-as-needed row per trial under a header") {
  TrialRecord t = trial("arc", 0, false, 1);
  t.failure = "exit 2: bad \"input\", really";
  std::ostringstream out;
  writeCsv({t}, out);
  std::istringstream in(out.str());
  std::string header, row, extra;
  std::getline(in, header);
  std::getline(in, row);
  CHECK_FALSE(std::getline(in, extra));
  CHECK(header.rfind("suite,robots,method,trial,seed,", 0) == 0);
  CHECK(row.find("\"exit 2: bad \"\"input\"\", really\"") != std::string::npos);
}

TEST_CASE("a method run with planner arguments is named with them in the tables, the CSV and the OMPL logs") {
  std::vector<TrialRecord> t = {trial("earc", 0, true, 1), trial("earc", 1, true, 2), trial("arc", 0, true, 3),
                                trial("arc", 1, true, 4)};
  for (int i : {0, 1}) t[i].planner_args = {"--db-k=5", "--window", "4"};
  const std::string table = markdownTable(t, {});
  CHECK(table.find("\n| 4 | earc --db-k=5 --window 4 | 2/2 (100%) |") != std::string::npos);
  CHECK(table.find("\n| 4 | arc | 2/2 (100%) |") != std::string::npos);  // none: the plain name
  CHECK(markdownWideTable(t).find("\n| robots | earc --db-k=5 --window 4 | arc |") != std::string::npos);
  std::ostringstream csv;
  writeCsv(t, csv);
  const auto csv_lines = [&] {
    std::vector<std::string> out;
    std::istringstream in(csv.str());
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
  }();
  REQUIRE(csv_lines.size() == 5);
  CHECK(csv_lines[0].find(",planner_args,scenario_file,") != std::string::npos);
  CHECK(csv_lines[1].find(",--db-k=5 --window 4,") != std::string::npos);
  CHECK(csv_lines[1].rfind("mobile,4,earc,0,", 0) == 0);  // the method column stays the method
  const auto rows = csvByColumn(csv.str());
  CHECK(rows[0].at("planner_args") == "--db-k=5 --window 4");
  CHECK(rows[2].at("planner_args").empty());
  TempPath dir("earc-ompl-logs-args");
  writeOmplLogs(t, dir.path);
  const auto log = lines(dir.path + "/mobile-4.log");
  CHECK(std::count(log.begin(), log.end(), "earc --db-k=5 --window 4") == 1);
  CHECK(std::count(log.begin(), log.end(), "arc") == 1);

  // Quoted as a shell (and shlex.join) would take them; a '|' kept from
  // ending the markdown cell.
  t[0].planner_args = t[1].planner_args = {"--x=a|b c", "--y=it's"};
  CHECK(plannerArgsText(t[0].planner_args) == R"('--x=a|b c' '--y=it'"'"'s')");
  CHECK(markdownTable(t, {}).find(R"(| 4 | earc '--x=a\|b c' '--y=it'"'"'s' |)") != std::string::npos);
  // Trials that mix sets (a results file never does) are not named after one.
  t[1].planner_args.clear();
  CHECK(markdownTable(t, {}).find("| 4 | earc (several sets of planner arguments) |") != std::string::npos);
}

TEST_CASE("planner arguments that earc-bench sets itself, or that would stop or confuse every plan, are refused") {
  using Args = std::vector<std::string>;
  for (const Args& ok : {Args{}, Args{"--db-k=5"}, Args{"--window", "4"}, Args{"--db-max-stretch=4", "--shadow-decoupled"},
                         Args{"--dbx"}, Args{"--db-k", "-1"}})
    CHECK_FALSE(plannerArgsProblem(ok).has_value());
  const std::pair<Args, const char*> refused[] = {
      {{"--seed=3"}, "'--seed=3' sets what earc-bench gives earc-plan itself (the scenario, -o, --method,"},
      {{"--time-limit", "5"}, "'--time-limit' sets what earc-bench gives earc-plan itself"},
      {{"--db=x.sqlite"}, "'--db=x.sqlite' sets what"},
      {{"--output=x"}, "'--output=x' sets what"},
      {{"-ox.json"}, "'-ox.json' sets what"},
      {{"--method=arc"}, "'--method=arc' sets what"},
      {{"--no-learn"}, "'--no-learn' sets what"},
      {{"--quiet"}, "'--quiet' sets what"},
      {{"-q"}, "'-q' sets what"},
      {{"--help"}, "'--help' would stop every plan before it planned"},
      {{"-h"}, "'-h' would stop every plan"},
      {{"--version"}, "'--version' would stop every plan"},
      {{"--"}, "'--' ends earc-plan's options"},
      {{"s.json"}, "'s.json' is not an option (nor the value of one): the scenario is earc-bench's to give"},
      {{"--window=4", "s.json"}, "'s.json' is not an option"},
      {{""}, "an empty argument"},
      {{"--x=a\nb"}, "'--x=a?b' has a control character or a byte that is not UTF-8 text"},
      {{"--x=\xff"}, "'--x=?' has a control character or a byte that is not UTF-8 text"},
  };
  for (const auto& [args, says] : refused) {
    CAPTURE(args.front());
    const auto why = plannerArgsProblem(args);
    REQUIRE(why.has_value());
    CHECK_MESSAGE(why->rfind(says, 0) == 0, *why);
  }
  CHECK_THROWS_WITH_AS(requirePlannerArgs({"--seed=3"}, "--new-arg"),
                       doctest::Contains("--new-arg: '--seed=3' sets what earc-bench gives"), InputError);
  CHECK(plannerArgsText({}).empty());
  CHECK(plannerArgsText({"--db-k=5", "--window", "4", "@%+=:,./-_"}) == "--db-k=5 --window 4 @%+=:,./-_");
}

TEST_CASE("OMPL benchmark logs follow Benchmark::saveResultsToStream's layout") {
  TempPath dir("earc-ompl-logs");
  std::vector<TrialRecord> t = {trial("arc", 0, true, 2), trial("earc", 0, true, 1), trial("arc", 1, false, 60),
                                trial("arc", 0, true, 5, "arms", 2)};
  const auto files = writeOmplLogs(t, dir.path);
  REQUIRE(files.size() == 2);
  const auto l = lines(dir.path + "/mobile-4.log");
  REQUIRE(l.size() > 20);
  CHECK(l[0] == "earc-bench version 1");
  CHECK(l[1] == "Experiment mobile-4");
  CHECK(l[2] == "3 experiment properties");
  CHECK(l[6].rfind("Running on ", 0) == 0);
  CHECK(l[7].rfind("Starting at ", 0) == 0);
  CHECK(l[8] == "<<<|");
  std::size_t i = 9;
  while (l[i] != "|>>>") ++i;
  CHECK(l[++i] == "<<<|");
  CHECK(l[++i] == "|>>>");
  CHECK(l[++i] == "1 is the random seed");
  CHECK(l[++i] == "60 seconds per run");
  CHECK(l[++i].find(" MB per run") != std::string::npos);
  CHECK(l[++i] == "2 runs per planner");
  CHECK(l[++i].find(" seconds spent to collect the data") != std::string::npos);
  CHECK(l[++i] == "1 enum type");
  CHECK(l[++i].rfind("status|", 0) == 0);
  CHECK(l[++i] == "2 planners");
  CHECK(l[++i] == "earc");  // methods in the tables' order
  CHECK(l[++i] == "0 common properties");
  CHECK(l[++i] == "10 properties for each run");
  const std::size_t props = i + 1;
  CHECK(l[props + 7] == "time REAL");
  CHECK(l[props + 4] == "solved BOOLEAN");
  i = props + 10;
  CHECK(l[i] == "1 runs");
  // Every value followed by "; ", the time where "time REAL" says.
  const std::string run = l[++i];
  CHECK(run.substr(run.size() - 2) == "; ");
  CHECK(std::count(run.begin(), run.end(), ';') == 10);
  CHECK(l[++i] == ".");
  CHECK(l[++i] == "arc");
}

TEST_CASE("OMPL log names from odd suite names stay inside the directory; the suites' names stay as they are") {
  TempPath parent("earc-ompl-escape");
  const std::string dir = parent.path + "/a/b/logs";
  std::vector<TrialRecord> t;
  for (const std::string suite : {"../../escaped", "..", "x/y", "x_y", ".hidden", "a\nb"})
    t.push_back(trial("arc", 0, true, 1, suite));
  for (const Suite& s : allSuites()) t.push_back(trial("arc", 0, true, 1, s.name));
  const auto files = writeOmplLogs(t, dir);
  CHECK(files.size() == t.size());  // no two suites share a file
  std::set<std::string> names;
  for (const auto& e : std::filesystem::recursive_directory_iterator(parent.path))
    if (e.is_regular_file()) {
      CHECK(e.path().parent_path() == std::filesystem::path(dir));
      const std::string name = e.path().filename().string();
      CHECK(name[0] != '.');
      CHECK(name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-") ==
            std::string::npos);
      names.insert(name);
    }
  CHECK(names.size() == t.size());
  for (const Suite& s : allSuites()) CHECK(names.count(s.name + "-4.log") == 1);
  // A line break in a name does not break the log's lines.
  int one_line = 0;
  for (const std::string& f : files)
    for (const std::string& line : lines(f)) {
      CHECK(line != "b");
      one_line += line == "suite TEXT = a b";
    }
  CHECK(one_line == 1);
}

TEST_CASE("export knows the OMPL logs' files before it writes them") {
  TempPath dir("earc-ompl-names");
  std::vector<TrialRecord> t = {trial("arc", 0, true, 1), trial("arc", 0, true, 1, "arms", 2),
                                trial("arc", 0, true, 1, "a/b")};
  t.push_back(trial("arc", 0, true, 1));
  t.back().time_limit_s = 30;  // two limits in one cell: -tl in the names
  const auto names = omplLogFiles(t, dir.path);
  CHECK(names == writeOmplLogs(t, dir.path));
  CHECK(std::count(names.begin(), names.end(), dir.path + "/mobile-4-tl30.log") == 1);
}

// earc-bench's counts and limits are checked as they are parsed.
TEST_CASE("count and limit validators refuse 0, signs, NaN and infinities") {
  auto verdict = [](const CLI::Validator& v, std::string text) { return v(text); };
  for (const char* bad : {"0", "00", "-1", "+1", "1.5", "", "x"})
    CHECK(verdict(cli::kPositiveWholeNumber, bad) == "'" + std::string(bad) + "' is not a whole number >= 1");
  CHECK(verdict(cli::kPositiveWholeNumber, "1").empty());
  CHECK(verdict(cli::kPositiveWholeNumber, "010").empty());
  CHECK(verdict(cli::kWholeNumber, "0").empty());
  for (const char* bad : {"nan", "inf", "-inf", "x"})
    CHECK(verdict(cli::kFinitePositive, bad) == "'" + std::string(bad) + "' is not a finite number");
  CHECK(verdict(cli::kFinitePositive, "0") == "0 is not positive");
  CHECK(verdict(cli::kFiniteNonNegative, "-1") == "-1 is negative");
  CHECK(verdict(cli::kFiniteNonNegative, "0").empty());
}

TEST_CASE("an output directory may be missing or a directory, never a file (plot -o, export --ompl-log)") {
  TempPath dir("earc-out-dir");
  std::filesystem::create_directories(dir.path);
  CHECK_NOTHROW(requireOutputDirectory(dir.path, "-o"));
  CHECK_NOTHROW(requireOutputDirectory(dir.path + "/new", "-o"));
  std::ofstream(dir.path + "/a-file") << "x";
  CHECK_THROWS_WITH_AS(requireOutputDirectory(dir.path + "/a-file", "--ompl-log"),
                       (dir.path + "/a-file: --ompl-log: exists and is not a directory").c_str(), InputError);
}

TEST_CASE("option checks refuse empty items and outputs that would overwrite the input") {
  CHECK(splitOptionList("2,4", "--robots") == std::vector<std::string>{"2", "4"});
  for (const char* bad : {"2,,4", "2,", ",2", ",", ""}) CHECK_THROWS_AS(splitOptionList(bad, "--robots"), InputError);
  CHECK_THROWS_WITH(splitOptionList("2,,4", "--robots"), "--robots: empty item in '2,,4'");
  CHECK_THROWS_WITH(suiteByName("bogus", "--suite"), doctest::Contains("--suite: unknown suite 'bogus'"));

  TempPath dir("earc-same-file");
  std::filesystem::create_directories(dir.path);
  const std::string results = dir.path + "/r.sqlite";
  std::ofstream(results) << "results";
  CHECK(sameFile(results, dir.path + "/./r.sqlite"));
  CHECK(sameFile(dir.path + "/x/../new.csv", dir.path + "/new.csv"));  // neither exists
  CHECK_FALSE(sameFile(results, dir.path + "/new.csv"));
  std::filesystem::create_symlink(results, dir.path + "/link");
  CHECK(sameFile(dir.path + "/link", results));
  CHECK_THROWS_AS(requireSeparateOutputs(results, "--results", {{dir.path + "/link", "--csv"}}), InputError);
  CHECK_THROWS_AS(requireSeparateOutputs(results, "--results", {{results + "-wal", "--csv"}}), InputError);
  CHECK_THROWS_AS(requireSeparateOutputs(results, "--results",
                                         {{dir.path + "/a.csv", "--csv"}, {dir.path + "/./a.csv", "--databases-csv"}}),
                  InputError);
  CHECK_NOTHROW(requireSeparateOutputs(results, "--results",
                                       {{"", "--csv"}, {"", "--databases-csv"}, {dir.path + "/a.csv", "--x"}}));
  CHECK(lines(results) == std::vector<std::string>{"results"});  // untouched
}

TEST_CASE("a trial's scenario is a function of suite, robots, trial and seed, and databases never hold it") {
  const Suite& s = suiteByName("mobile-obst");
  CHECK(trialSeeds(s, 4, 0, 1).scenario == trialSeeds(s, 4, 0, 1).scenario);
  CHECK(trialSeeds(s, 4, 0, 1).scenario != trialSeeds(s, 4, 1, 1).scenario);
  CHECK(trialSeeds(s, 4, 0, 1).scenario != trialSeeds(suiteByName("mobile"), 4, 0, 1).scenario);
  const Scenario a = trialScenario(s, 4, 0, 1), b = trialScenario(s, 4, 0, 1);
  CHECK(a.name == "mobile-obst-4-t0");
  CHECK(a.robots.size() == 4);
  CHECK(a.obstacles.size() > 0);
  CHECK(a.robots[0].start == b.robots[0].start);
  const Scenario d = databaseProblem(s, 4, 0, 1);
  CHECK(d.robots[0].start != a.robots[0].start);
  CHECK_THROWS_AS(suiteByName("boats"), InputError);
  CHECK(splitList("a,,b,") == std::vector<std::string>{"a", "b"});
}

TEST_CASE("the MovingAI suites put robots on the compiled-in maps, which are the files in datasets/movingai") {
  // Every map in the folder is compiled in, unchanged.
  std::size_t files = 0;
  for (const auto& f : std::filesystem::directory_iterator(std::filesystem::path(EARC_SOURCE_DIR) / "datasets" / "movingai")) {
    if (f.path().extension() != ".map") continue;
    ++files;
    const gen::EmbeddedMap* m = gen::findEmbeddedMovingAiMap(f.path().stem().string());
    REQUIRE_MESSAGE(m != nullptr, f.path());
    CHECK(m->text == readTextFile(f.path().string()));
  }
  CHECK(files == gen::embeddedMovingAiMaps().size());
  CHECK(gen::findEmbeddedMovingAiMap("no-such-map") == nullptr);
  // And every scenario file.
  std::size_t scens = 0;
  for (const auto& f : std::filesystem::directory_iterator(std::filesystem::path(EARC_SOURCE_DIR) / "datasets" / "movingai")) {
    if (f.path().extension() != ".scen") continue;
    ++scens;
    const gen::EmbeddedMap* m = gen::findEmbeddedMovingAiScen(f.path().stem().string());
    REQUIRE_MESSAGE(m != nullptr, f.path());
    CHECK(m->text == readTextFile(f.path().string()));
  }
  CHECK(scens == gen::embeddedMovingAiScens().size());

  int paper = 0;
  for (const Suite& s : allSuites()) {
    paper += s.paper() ? 1 : 0;
    if (s.map.empty()) continue;
    CAPTURE(s.name);
    CHECK_FALSE(s.paper());
    CHECK(s.family == "mobile");  // E-ARC answers them from the mobile database
    const std::optional<gen::GridMap> embedded = gen::embeddedMovingAiMap(s.map);
    REQUIRE(embedded.has_value());
    const gen::GridMap& map = *embedded;
    const Scenario a = trialScenario(s, 8, 0, 1), b = trialScenario(s, 8, 0, 1), c = trialScenario(s, 8, 1, 1);
    CHECK(a.name == s.name + "-8-t0");
    CHECK(a.robots.size() == 8);
    CHECK(a.obstacles.size() == gen::mergeBlockedCells(map).size());
    CHECK(a.workspace.hi.x == map.width);
    CHECK(a.workspace.hi.y == map.height);
    for (std::size_t i = 0; i < a.robots.size(); ++i) CHECK(a.robots[i].start == b.robots[i].start);
    // A crowd suite's trials are all its file's first agents.
    if (s.crowd())
      CHECK(a.robots[0].start == c.robots[0].start);
    else
      CHECK(a.robots[0].start != c.robots[0].start);
    CHECK(databaseProblem(s, 8, 0, 1).robots[0].start != a.robots[0].start);
  }
  CHECK(paper == 4);
  CHECK(suiteByName("movingai-den520d").map == "den520d");
}
