// The Lightning baseline: whole-problem plans that validate, its database
// growing, saving, reloading, and refusing files of another space.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

#include "earc/baselines/lightning.hpp"
#include "earc/gen/generators.hpp"
#include "earc/io/input_error.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/methods.hpp"
#include "earc/validate/validator.hpp"

using namespace earc;

namespace {

Scenario twoMobile(std::uint64_t seed, int obstacles = 4) {
  gen::MobileSettings s;
  s.robots = 2;
  s.obstacles = obstacles;
  s.workspace = 8.0;
  s.seed = seed;
  return gen::generateMobile(s);
}

Scenario twoArms(std::uint64_t seed) {
  gen::ArmSettings s;
  s.robots = 2;
  s.seed = seed;
  return gen::generateArms(s);
}

PlannerSettings settings(std::uint64_t seed) {
  PlannerSettings s;
  s.method = Method::Lightning;
  s.time_limit_s = 20.0;
  s.seed = seed;
  return s;
}

struct TempFile {
  std::string path;
  explicit TempFile(const std::string& name)
      : path((std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()))).string()) {
    std::filesystem::remove(path);
  }
  ~TempFile() { std::filesystem::remove(path); }
};

}  // namespace

TEST_CASE("Lightning solves a two-robot mobile scenario with a solution the validator accepts") {
  const Scenario s = twoMobile(3);
  PlanResult r = plan(s, settings(1));
  REQUIRE(r.solution.solved);
  CHECK(r.failures.empty());
  CHECK(validateSolution(s, r.solution).valid);
  CHECK(r.stats.lightning->lightning_source == "scratch");  // the database was empty
  CHECK(r.stats.makespan.has_value());
  CHECK(r.stats.planning_time_s.value_or(1e9) <= 20.0);
}

TEST_CASE("plan() dispatches to Lightning and validates its solution") {
  const Scenario s = twoMobile(5);
  PlanResult r = plan(s, settings(2));
  REQUIRE(r.solution.solved);
  CHECK(r.solution.method == "lightning");
  CHECK(r.stats.lightning->lightning_db_entries == 0);  // no database file: an empty one
}

TEST_CASE("Lightning plans two facing arms") {
  const Scenario s = twoArms(4);
  PlanResult r = plan(s, settings(3));
  REQUIRE(r.solution.solved);
  CHECK(validateSolution(s, r.solution).valid);
}

TEST_CASE("a Lightning database grows by the first solution, survives a save and reload, and serves recall") {
  TempFile file("earc-lightning-db");
  const Scenario s = twoMobile(7);
  {
    LightningDatabase db(s);
    CHECK(db.entries() == 0);
    PlanResult r = db.plan(s, settings(1), earc::LightningSettings{});
    REQUIRE(r.solution.solved);
    CHECK(db.entries() == 1);
    CHECK(r.stats.lightning->lightning_db_added == 1);
    db.save(file.path);
  }
  LightningDatabase again(s);
  again.load(file.path);
  CHECK(again.entries() == 1);
  CHECK(again.states() >= 2);
  // The same problem again, through plan() with the file and without
  // learning: either thread may win the race, but the plan must be valid
  // whichever did, and the file stays as it was.
  const auto size = std::filesystem::file_size(file.path);
  PlannerSettings st = settings(9);
  st.db.lightning_file = file.path;
  st.db.learn = false;
  PlanResult r = plan(s, st);
  REQUIRE(r.solution.solved);
  CHECK(r.stats.lightning->lightning_db_entries == 1);
  CHECK(std::filesystem::file_size(file.path) == size);
}

TEST_CASE("planning without learning leaves a Lightning database as it was") {
  const Scenario s = twoMobile(11);
  LightningDatabase db(s);
  earc::LightningSettings ls;
  ls.learn = false;
  PlanResult r = db.plan(s, settings(1), ls);
  REQUIRE(r.solution.solved);
  CHECK(db.entries() == 0);
  CHECK(r.stats.lightning->lightning_db_added == 0);
}

TEST_CASE("a Lightning database of another state space is refused with a message naming the file") {
  TempFile file("earc-lightning-foreign");
  const Scenario mobile = twoMobile(13);
  {
    LightningDatabase db(mobile);
    REQUIRE(db.plan(mobile, settings(1), earc::LightningSettings{}).solution.solved);
    db.save(file.path);
  }
  LightningDatabase arms(twoArms(2));
  CHECK_THROWS_AS(arms.load(file.path), InputError);
  try {
    arms.load(file.path);
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find(file.path) != std::string::npos);
    CHECK(std::string(e.what()).find("2 robots (2 arms)") != std::string::npos);
  }
  // A file of an older format (v1: a compound OMPL space, which OMPL's
  // loader cannot read into today's space) is refused by its version.
  {
    std::string bytes;
    {
      std::ifstream in(file.path, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    const std::size_t tag = bytes.rfind("\nearc-lightning v2 ");
    REQUIRE(tag != std::string::npos);
    bytes[tag + 17] = '1';
    std::ofstream(file.path, std::ios::binary) << bytes;
    LightningDatabase older(mobile);
    CHECK_THROWS_WITH_AS(older.load(file.path), doctest::Contains("Lightning database format v1, this earc reads v2"),
                         InputError);
  }
  std::ofstream(file.path) << "not a database\n";
  LightningDatabase m(mobile);
  CHECK_THROWS_AS(m.load(file.path), InputError);
}

TEST_CASE("a Lightning database file is created when missing, and only then") {
  TempFile file("earc-lightning-create");
  const Scenario s = twoMobile(17);
  PlannerSettings st = settings(1);
  st.db.lightning_file = file.path;
  PlanResult r = plan(s, st);
  REQUIRE(r.solution.solved);
  CHECK(std::filesystem::exists(file.path));
  LightningDatabase db(s);
  db.load(file.path);
  CHECK(db.entries() == 1);
}

TEST_CASE("with an empty database Lightning is RRT-Connect alone and repeats itself for one seed") {
  // Retrieve-and-repair gives up at once on an empty database, so no race
  // decides the result: the same seed must give the same solution.
  const Scenario s = twoMobile(19);
  PlanResult a = planLightning(s, settings(4)), b = planLightning(s, settings(4));
  REQUIRE(a.solution.solved);
  REQUIRE(b.solution.solved);
  REQUIRE(a.solution.paths.size() == b.solution.paths.size());
  for (std::size_t r = 0; r < a.solution.paths.size(); ++r) CHECK(a.solution.paths[r] == b.solution.paths[r]);
}
