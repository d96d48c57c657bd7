// Helpers shared by the results database's tests (test_bench_results*.cpp):
// scratch files, trial records, files made as older versions left them.
#pragma once

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

namespace earc::bench_test {

using namespace earc::bench;

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

inline TrialRecord trial(const std::string& method, int t, bool ok, double secs, const std::string& suite = "mobile",
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
inline std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// writeCsv's text as rows of (column name, field), the header's names,
// the fields unquoted (RFC 4180: "" in quotes is "); every row as wide as
// the header.
inline std::vector<std::map<std::string, std::string>> csvByColumn(const std::string& text) {
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
inline void makeOlder(const std::string& path, int version) {
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
inline std::vector<TrialRecord> readOldThenMigrate(const std::string& path, int version,
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

inline std::vector<TrialRecord> checkBuildColumn(const BuildColumn& col, const std::string& path) {
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

inline LightningSettings perRobotLightning(int per_robot, double time_limit_s) {
  LightningSettings l;
  l.problems_per_robot = per_robot;
  l.problem_time_limit_s = time_limit_s;
  return l;
}

inline TrialRecord lightningTrial(int t, const LightningSettings& settings) {
  TrialRecord r = trial("lightning", t, true, 1.0);
  r.lightning = settings;
  return r;
}

inline TrialRecord earcTrial(int t, bool learn, const std::string& db, std::optional<std::int64_t> state) {
  TrialRecord r = trial("earc", t, true, 1.0);
  r.learn = learn;
  r.earc_db = db;
  r.earc_db_state = state;
  return r;
}

}  // namespace earc::bench_test
