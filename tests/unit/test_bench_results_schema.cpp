// The results database's migrations: embedded as the files in
// migrations/results/ are, and a file migrated from version 1 ends with
// the schema a new file gets.
#include <doctest/doctest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "earc/bench/results_db.hpp"
#include "earc/bench/results_migrations.hpp"
#include "earc/experience/scratch.hpp"
#include "earc/experience/sqlite.hpp"
#include "support.hpp"

using namespace earc;
using namespace earc::bench;

namespace {

// Every table's and index's definition as SQLite keeps it, in name order.
std::vector<std::string> resultsSchemaOf(const std::string& path) {
  exp::Connection c(path, exp::OpenMode::ReadOnly);
  exp::Statement s = c.prepare("SELECT type || ' ' || name || ': ' || ifnull(sql, '') FROM sqlite_master ORDER BY name");
  std::vector<std::string> out;
  while (s.step()) out.push_back(s.textAt(0));
  return out;
}

}  // namespace

TEST_CASE("the embedded results migrations are byte for byte the files in migrations/results/") {
  const std::filesystem::path dir = std::filesystem::path(EARC_SOURCE_DIR) / "migrations" / "results";
  std::set<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".sql") files.insert(entry.path().filename().string());
  std::set<std::string> embedded;
  int expected_version = 1;
  for (const ResultsMigration& m : resultsMigrations()) {
    CHECK(m.version == expected_version++);
    embedded.insert(std::string(m.name));
    CHECK_MESSAGE(earc::test::readFile(dir / m.name) == m.sql, "migration " << m.name << " differs from its file");
  }
  CHECK(files == embedded);
  CHECK(static_cast<int>(resultsMigrations().size()) == kResultsSchemaVersion);
}

TEST_CASE("a results file migrated from each older version gets the schema of a new one") {
  exp::ScratchDirectory dir("results-schema");
  const std::string fresh = dir.file("fresh.sqlite");
  { ResultsDb db(fresh); }
  const std::vector<std::string> want = resultsSchemaOf(fresh);
  {
    // Version 1's columns, then those of versions 2 to 9 in their order.
    exp::Connection c(fresh, exp::OpenMode::ReadOnly);
    exp::Statement s = c.prepare("SELECT group_concat(name, ' ') FROM pragma_table_info('trials')");
    REQUIRE(s.step());
    CHECK(s.textAt(0) ==
          "id suite robots method trial seed time_limit_s scenario_seed planner_seed success planning_time_s "
          "wall_time_s makespan sum_of_costs conflicts db_hits peak_memory_kb exit_status term_signal failure "
          "finished_at jobs planner_version bench_version planner_args scenario_file lightning_problems "
          "lightning_problems_per_robot lightning_problem_time_limit_s learn earc_db earc_db_state lower_bound "
          "refine_first_time_s refine_first_sum_of_costs refine_final_sum_of_costs refine_final_makespan");
  }
  for (int version = 1; version < kResultsSchemaVersion; ++version) {
    CAPTURE(version);
    const std::string old = dir.file("v" + std::to_string(version) + ".sqlite");
    {
      // The file an earc-bench of that version made: its migrations only.
      exp::Connection c(old, exp::OpenMode::ReadWrite);
      for (const ResultsMigration& m : resultsMigrations())
        if (m.version <= version) c.exec(m.sql);
      c.exec("PRAGMA application_id = " + std::to_string(kResultsApplicationId));
      c.exec("PRAGMA user_version = " + std::to_string(version));
    }
    { ResultsDb db(old, true); }  // read as it is
    {
      exp::Connection c(old, exp::OpenMode::ReadOnly);
      CHECK(c.pragmaInt("user_version") == version);
    }
    { ResultsDb db(old); }  // opened for writing: migrated
    exp::Connection c(old, exp::OpenMode::ReadOnly);
    CHECK(c.pragmaInt("user_version") == kResultsSchemaVersion);
    CHECK(resultsSchemaOf(old) == want);
  }
}
