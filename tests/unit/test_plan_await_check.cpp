// planThenAwaitCheck: the store's background check, awaited after the plan;
// a write it could not make is reported in the plan's stats and its file.
#include <doctest/doctest.h>

#include "earc/experience/sqlite.hpp"
#include "earc/experience/store.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/planner.hpp"
#include "support.hpp"

using namespace earc;
using earc::test::TempDb;

namespace {

// Two discs on parallel lanes far apart: planned without a conflict, so
// E-ARC queries and learns nothing and the session count is the first write.
Scenario apartLanes() {
  Scenario s;
  s.name = "apart";
  s.workspace = {{0, 0}, {10, 10}};
  for (double y : {1.0, 9.0}) {
    RobotSpec r;
    r.name = "r" + std::to_string(static_cast<int>(y));
    r.kind = RobotKind::Mobile;
    r.shape = MobileShape::Disc;
    r.radius = 0.3;
    r.start = {1, y, 0};
    r.goal = {9, y, 0};
    s.robots.push_back(r);
  }
  return s;
}

}  // namespace

TEST_CASE("A session count the disk has no room for reaches the solution file's stats") {
  TempDb tmp;
  { exp::ExperienceStore made(tmp.file()); }  // ours, in WAL mode: opened with the check in the background
  exp::StoreOptions options;
  options.check_in_background = true;
  options.check_in_open_when_busy = false;
  exp::ExperienceStore store(tmp.file(), options);
  // A full disk, as SQLite reports it (SQLITE_FULL): no page may be added,
  // and the session count first writes 4 MB (a temporary trigger).
  exp::Connection& c = store.connection();
  c.exec("PRAGMA max_page_count = " + std::to_string(c.pragmaInt("page_count")));
  c.exec("CREATE TEMP TRIGGER no_room BEFORE UPDATE ON main.store_meta BEGIN "
         "INSERT INTO history (token, at, program, operation, detail) "
         "VALUES (0, 0, 'test', 'learn', zeroblob(4000000)); END");
  PlannerSettings settings;
  settings.method = Method::Earc;
  settings.time_limit_s = 30;
  // Planning alone writes nothing: the loss is the check's session count.
  CHECK_FALSE(plan(apartLanes(), settings, &store).stats.db_learn_error);
  const PlanResult r = planThenAwaitCheck(apartLanes(), settings, store);
  REQUIRE(r.solution.solved);
  REQUIRE(r.stats.db_learn_error);
  CHECK(r.stats.db_learn_error->find("the disk is full") != std::string::npos);
  // What saveSolution writes.
  CHECK(r.solution.stats.value("db_learn_error", "") == *r.stats.db_learn_error);
  CHECK(PlanStats::fromJson(r.solution.stats).db_learn_error == r.stats.db_learn_error);
}
