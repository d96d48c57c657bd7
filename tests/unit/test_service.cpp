// The planner service's protocol (earc/service/service.hpp): bad requests
// get one-line errors and the service goes on, solutions are validated,
// learned rows are reported by id and committed, other processes' rows are
// picked up, and a stop request cuts planning short.
#include <doctest/doctest.h>
#include <sys/stat.h>

#include "earc/experience/scratch.hpp"
#include "earc/experience/store.hpp"
#include "earc/io/json_io.hpp"
#include "earc/methods/plan.hpp"
#include "earc/planning/planner.hpp"
#include "earc/service/service.hpp"
#include "earc/util/deadline.hpp"
#include "earc/validate/scenario_check.hpp"
#include "earc/validate/validator.hpp"

using namespace earc;
using nlohmann::json;

namespace {

// 16 mobile robots among obstacles: ARC meets 8 conflicts with seed 3,
// and E-ARC learns how each was resolved.
const std::string kScenarioFile = EARC_SOURCE_DIR "/datasets/mobile-obst-16-s1.json";
Scenario serviceScenario() { return loadScenario(kScenarioFile); }

json reply(service::Service& svc, const std::string& line) {
  const std::string out = svc.handleLine(line);
  CHECK(out.find('\n') == std::string::npos);  // one line per response
  return json::parse(out);
}

}  // namespace

TEST_CASE("serve protocol: the service answers bad requests with one-line errors and keeps serving") {
  exp::ScratchDirectory dir("service-errors");
  auto store = std::make_shared<exp::ExperienceStore>(dir.file("s.db"));
  service::Service svc(store, {});

  json r = reply(svc, "{\"id\": 1, \"scenario\": ");  // cut off
  CHECK(r["ok"] == false);
  CHECK(r["id"].is_null());
  CHECK(r["error"].get<std::string>().find("malformed JSON") != std::string::npos);

  r = reply(svc, "[1, 2]");
  CHECK(r["ok"] == false);
  CHECK(r["error"].get<std::string>().find("must be a JSON object") != std::string::npos);

  r = reply(svc, R"({"id": "a", "op": "fly"})");
  CHECK(r["id"] == "a");
  CHECK(r["ok"] == false);
  CHECK(r["error"].get<std::string>().find("unknown op") != std::string::npos);

  json bad = scenarioToJson(serviceScenario());
  bad["robots"][2]["start"][0] = 600.0;  // outside the workspace
  r = reply(svc, json{{"id", 7}, {"scenario", bad}, {"method", "arc"}}.dump());
  CHECK(r["id"] == 7);
  CHECK(r["ok"] == false);
  const std::string why = r["error"].get<std::string>();
  CHECK(why.find("$.robots[2]") != std::string::npos);

  json none = scenarioToJson(serviceScenario());
  none["robots"] = json::array();
  r = reply(svc, json{{"id", 11}, {"scenario", none}}.dump());
  CHECK(r["ok"] == false);
  CHECK(r["error"].get<std::string>().find("scenario: $.robots: empty") != std::string::npos);

  r = reply(svc, json{{"id", 8}, {"scenario", scenarioToJson(serviceScenario())}, {"time_limt", 3}}.dump());
  CHECK(r["ok"] == false);
  CHECK(r["error"].get<std::string>().find("$.time_limt") != std::string::npos);

  r = reply(svc, json{{"id", 9}, {"scenario", scenarioToJson(serviceScenario())}, {"time_limit", -1}}.dump());
  CHECK(r["ok"] == false);
  CHECK(r["error"].get<std::string>().find("$.time_limit") != std::string::npos);

  REQUIRE(::mkfifo(dir.file("fifo.json").c_str(), 0600) == 0);
  r = reply(svc, json{{"id", 12}, {"scenario_file", dir.file("fifo.json")}}.dump());
  CHECK(r["ok"] == false);
  CHECK(r["error"].get<std::string>().find("fifo.json: scenario_file: not a regular file") != std::string::npos);

  r = reply(svc, json{{"id", 10}, {"scenario_file", dir.file("missing.json")}}.dump());
  CHECK(r["ok"] == false);
  CHECK(r["error"].get<std::string>().find("missing.json") != std::string::npos);

  r = reply(svc, json{{"id", 12}, {"scenario_file", kScenarioFile}, {"method", "arc"}, {"db_k", 3}}.dump());
  CHECK(r["ok"] == false);
  CHECK(r["error"].get<std::string>().find("$.db_k: is for method earc") != std::string::npos);

  r = reply(svc, json{{"id", 13}, {"scenario_file", kScenarioFile}, {"db_max_stretch", -1}}.dump());
  CHECK(r["ok"] == false);
  CHECK(r["error"].get<std::string>().find("$.db_max_stretch: must be a number >= 0") != std::string::npos);
  for (const json& bad : {json(0), json(1001), json(2.5), json(-1), json("3")}) {
    r = reply(svc, json{{"id", 14}, {"scenario_file", kScenarioFile}, {"db_k", bad}}.dump());
    CHECK(r["ok"] == false);
    CHECK(r["error"].get<std::string>().find("$.db_k: must be a whole number from 1 to 1000") != std::string::npos);
  }
  r = reply(svc, json{{"id", 16}, {"scenario_file", kScenarioFile}, {"compact", 1}}.dump());
  CHECK(r["ok"] == false);
  CHECK(r["error"].get<std::string>().find("$.compact: must be true or false") != std::string::npos);

  r = reply(svc, json{{"id", 15}, {"scenario_file", kScenarioFile}, {"db_repair_max", 1001}}.dump());
  CHECK(r["error"].get<std::string>().find("$.db_repair_max: must be a whole number from 0 to 1000") !=
        std::string::npos);

  r = reply(svc, R"({"id": 11, "op": "ping"})");
  CHECK(r["ok"] == true);
  CHECK(r["protocol"] == service::kProtocol);
  CHECK(svc.counters().errors == 18);
  CHECK(svc.counters().requests == 19);
}

TEST_CASE("serve protocol: the service plans through the validator and reports what it learned by id") {
  exp::ScratchDirectory dir("service-learn");
  const std::string path = dir.file("s.db");
  auto store = std::make_shared<exp::ExperienceStore>(path);
  service::Service svc(store, {});
  const Scenario scenario = serviceScenario();
  json r = reply(svc, json{{"id", "first"}, {"scenario", scenarioToJson(scenario)}, {"seed", 3}}.dump());
  REQUIRE(r["ok"] == true);
  CHECK(r["id"] == "first");
  REQUIRE(r["solved"] == true);
  CHECK(r["interrupted"] == false);
  const Solution sol = solutionFromJson(r["solution"], &scenario, "response");
  CHECK(validateSolution(scenario, sol).valid);
  const json& st = r["stats"];
  CHECK(st["method"] == "earc");
  const auto ids = st["db_learned_ids"].get<std::vector<std::int64_t>>();
  CHECK(ids.size() == st["db_learned"].get<std::size_t>());
  REQUIRE(!ids.empty());
  CHECK(st["db_entries"].get<std::size_t>() == st["db_entries_before"].get<std::size_t>() + ids.size());
  // Committed before the response: another connection sees every row.
  {
    exp::StoreOptions ro;
    ro.read_only = true;
    exp::ExperienceStore other(path, ro);
    for (std::int64_t id : ids) CHECK(other.get(id).has_value());
  }
  CHECK(svc.counters().learned == static_cast<std::int64_t>(ids.size()));

  // The same problem again: now solved from the database, nothing new.
  r = reply(svc, json{{"id", "again"}, {"scenario", scenarioToJson(scenario)}, {"seed", 3}}.dump());
  REQUIRE(r["solved"] == true);
  const int answered_again = r["stats"]["db_hits"].get<int>() + r["stats"]["db_repairs"].get<int>();
  CHECK(answered_again >= 1);

  // E-ARC's retrieval settings per request: a bound of one straight
  // motion refuses answers that wait or turn aside, and the plan still
  // solves from scratch; db_k and db_repair_max are taken.
  r = reply(svc, json{{"id", "strict"}, {"scenario", scenarioToJson(scenario)}, {"seed", 3}, {"learn", false},
                      {"db_max_stretch", 1.0}, {"db_k", 2}, {"db_repair_max", 0}}
                     .dump());
  REQUIRE(r["solved"] == true);
  const int refused_strict = r["stats"]["db_refused_too_long"].get<int>();
  CHECK(refused_strict >= 1);
  CHECK(r["stats"]["db_repairs"].get<int>() == 0);
  const int answered_strict = r["stats"]["db_hits"].get<int>();
  CHECK_FALSE(r["stats"].contains("compact"));
  CHECK(validateSolution(scenario, solutionFromJson(r["solution"], &scenario, "response")).valid);
  r = reply(svc, R"({"op": "stats"})");
  CHECK(r["stats"]["plans"] == 3);
  CHECK(r["stats"]["solved"] == 3);
  // The session's database answers: the second and third plans' (the
  // first had an empty database).
  const json& session = r["stats"];
  const int answered = answered_again + answered_strict;
  CHECK(session["db_answered"].get<int>() == answered);
  CHECK(session["db_subproblems"].get<int>() > answered);
  CHECK(session["db_refused_too_long"].get<int>() == refused_strict);
  CHECK(session["db_hit_rate"].get<double>() ==
        doctest::Approx(static_cast<double>(answered) / session["db_subproblems"].get<int>()));
  // Compaction per request: its stats, and a plan no longer than without.
  r = reply(svc, json{{"id", "compact"}, {"scenario", scenarioToJson(scenario)}, {"seed", 3}, {"learn", false},
                      {"db_max_stretch", 1.0}, {"db_k", 2}, {"db_repair_max", 0}, {"compact", true}}
                     .dump());
  REQUIRE(r["solved"] == true);
  REQUIRE(r["stats"].contains("compact"));
  CHECK(r["stats"]["sum_of_costs"] <= r["stats"]["compact"]["sum_of_costs_before"]);
  CHECK(validateSolution(scenario, solutionFromJson(r["solution"], &scenario, "response")).valid);

  svc.close();
}

TEST_CASE("serve protocol: an answer carries the warnings earc-plan plan would give") {
  exp::ScratchDirectory dir("service-warnings");
  auto store = std::make_shared<exp::ExperienceStore>(dir.file("s.db"));
  service::Service svc(store, {});
  // An empty database: nothing to warn of.
  json r = reply(svc, json{{"scenario", scenarioToJson(serviceScenario())}, {"seed", 3}}.dump());
  REQUIRE(r["solved"] == true);
  CHECK_FALSE(r.contains("warnings"));
  REQUIRE(store->size() > 0);
  // Now it holds experiences of boxes only: discs get none of them.
  Scenario discs = loadScenario(EARC_TEST_DATA_DIR "/scenarios/swap-discs.json");
  r = reply(svc, json{{"scenario", scenarioToJson(discs)}, {"learn", false}}.dump());
  REQUIRE(r["ok"] == true);
  REQUIRE(r["warnings"].size() == 1);
  CHECK(r["warnings"][0].get<std::string>().find("none for these robots") != std::string::npos);
  // ARC reads no database; a resolution that steps through the
  // scenario's obstacles is said whatever the method.
  r = reply(svc, json{{"scenario", scenarioToJson(discs)}, {"method", "arc"}}.dump());
  CHECK_FALSE(r.contains("warnings"));
  discs.resolution.translation = 2.0;
  discs.obstacles.push_back(Obstacle::makeBox({5, 0.5}, {0.01, 0.01}));
  r = reply(svc, json{{"scenario", scenarioToJson(discs)}, {"method", "arc"}}.dump());
  REQUIRE(r["warnings"].size() == 1);
  CHECK(r["warnings"][0].get<std::string>().rfind("resolution: robot", 0) == 0);
  // An unknown key in the scenario, first.
  json typo = scenarioToJson(discs);
  typo["obstacles"][0]["angel"] = 0.5;
  r = reply(svc, json{{"scenario", typo}, {"method", "arc"}}.dump());
  REQUIRE(r["warnings"].size() == 2);
  CHECK(r["warnings"][0] == "scenario: $.obstacles[0].angel: unknown key, ignored (did you mean \"angle\"?)");
  svc.close();
}

TEST_CASE("serve protocol: the service picks up experiences another connection inserted since the last request") {
  exp::ScratchDirectory dir("service-refresh");
  const std::string path = dir.file("s.db");
  auto store = std::make_shared<exp::ExperienceStore>(path);
  service::Service svc(store, {});
  json r = reply(svc, R"({"op": "stats"})");
  CHECK(r["stats"]["db_entries"] == 0);
  {
    // Another writer (a second connection, as another process would be)
    // learns the scenario's conflicts.
    exp::ExperienceStore writer(path);
    PlannerSettings s;
    s.method = Method::Earc;
    s.seed = 3;
    REQUIRE(plan(serviceScenario(), s, &writer).solution.solved);
    REQUIRE(writer.size() > 0);
  }
  r = reply(svc, json{{"scenario", scenarioToJson(serviceScenario())}, {"seed", 3}}.dump());
  REQUIRE(r["solved"] == true);
  CHECK(r["stats"]["db_entries_before"].get<std::size_t>() > 0);
  CHECK(r["stats"]["db_hits"].get<int>() + r["stats"]["db_repairs"].get<int>() >= 1);
}

TEST_CASE("serve protocol: a stop request cuts the planning request in flight short and says so") {
  exp::ScratchDirectory dir("service-stop");
  auto store = std::make_shared<exp::ExperienceStore>(dir.file("s.db"));
  service::Service svc(store, {});
  svc.requestStop();
  Stopwatch clock;
  json r = reply(svc, json{{"id", 1}, {"scenario", scenarioToJson(serviceScenario())}, {"time_limit", 30}}.dump());
  svc.clearStop();
  CHECK(clock.seconds() < 5.0);
  CHECK(r["ok"] == true);
  CHECK(r["interrupted"] == true);
  CHECK(r["solved"] == false);
  CHECK(!r.contains("solution"));
  // And the next request plans normally again.
  r = reply(svc, json{{"id", 2}, {"scenario", scenarioToJson(serviceScenario())}, {"method", "arc"}}.dump());
  CHECK(r["interrupted"] == false);
  CHECK(r["solved"] == true);
}

TEST_CASE("serve protocol: the line splitter yields whole lines across reads and skips an overlong one") {
  service::LineSplitter split(10);
  auto a = split.feed("{\"a\":1}\r\n{\"b\"");
  REQUIRE(a.size() == 1);
  CHECK(a[0].text == "{\"a\":1}");
  auto b = split.feed(":2}\n\n   \n0123456789ABCDEF");
  REQUIRE(b.size() == 2);
  CHECK(b[0].text == "{\"b\":2}");
  CHECK(b[1].too_long);
  auto c = split.feed("GHIJ\nok\n");
  REQUIRE(c.size() == 1);
  CHECK(c[0].text == "ok");
  CHECK(!c[0].too_long);
  split.feed("tail");
  auto d = split.finish();
  REQUIRE(d.size() == 1);
  CHECK(d[0].text == "tail");
  CHECK(split.finish().empty());
}

TEST_CASE("serve protocol: a second request on the same world plans on the first one's roadmaps, to the same answer") {
  exp::ScratchDirectory dir("service-roadmaps");
  auto store = std::make_shared<exp::ExperienceStore>(dir.file("s.db"));
  // Budgets counted in work: timed ones can change the plan on a busy machine.
  const std::string request =
      json{{"scenario", scenarioToJson(serviceScenario())}, {"method", "arc"}, {"seed", 3}, {"deterministic", true}}
          .dump();
  service::Service svc(store, {});
  const json first = reply(svc, request), second = reply(svc, request);
  REQUIRE(first["solved"] == true);
  REQUIRE(second["solved"] == true);
  const auto built = first["stats"]["roadmaps_built"].get<std::size_t>();
  REQUIRE(built > 0);
  CHECK(first["stats"]["roadmaps_reused"] == 0);
  CHECK(second["stats"]["roadmaps_reused"] == built);
  CHECK(second["solution"]["paths"] == first["solution"]["paths"]);
  const json st = reply(svc, R"({"op": "stats"})")["stats"]["roadmap_cache"];
  CHECK(st["roadmaps"] == built);
  CHECK(st["reused"] == built);
  CHECK(st["bytes"].get<std::size_t>() > 0);
  CHECK(st["capacity_bytes"] == std::size_t{256} << 20);

  // None kept: every request builds its own.
  service::ServiceSettings none;
  none.roadmap_cache_mib = 0;
  service::Service plain(store, none);
  const json fresh = reply(plain, request);
  CHECK(fresh["solution"]["paths"] == first["solution"]["paths"]);
  CHECK_FALSE(fresh["stats"].contains("roadmaps_reused"));
  CHECK_FALSE(reply(plain, R"({"op": "stats"})")["stats"].contains("roadmap_cache"));
}

TEST_CASE("serve protocol: a service given a stop flag watches it, and its stop requests set it") {
  exp::ScratchDirectory dir("service-given-stop");
  auto store = std::make_shared<exp::ExperienceStore>(dir.file("s.db"));
  StopFlag stop{true};
  service::Service svc(store, {}, &stop);
  json r = reply(svc, json{{"id", 1}, {"scenario", scenarioToJson(serviceScenario())}, {"time_limit", 30}}.dump());
  CHECK(r["interrupted"] == true);
  CHECK(r["solved"] == false);
  svc.clearStop();
  CHECK(!stop.load());
  r = reply(svc, json{{"id", 2}, {"scenario", scenarioToJson(serviceScenario())}, {"method", "arc"}}.dump());
  CHECK(r["interrupted"] == false);
  CHECK(r["solved"] == true);
  svc.requestStop();
  CHECK(stop.load());
}

TEST_CASE("serve protocol: a response line holds the paths handle() gives, bit for bit") {
  // handleLine prints a plan's paths straight from memory; handle() builds
  // them as JSON. Two services, one deterministic plan each.
  service::Service by_line(nullptr, {});
  service::Service by_tree(nullptr, {});
  const json request = {{"id", 4}, {"scenario_file", kScenarioFile}, {"method", "arc"}, {"seed", 3}, {"deterministic", true}};
  const std::string line = by_line.handleLine(request.dump());
  const json tree = by_tree.handle(request);
  REQUIRE(tree["solved"] == true);
  const std::string paths_text = tree["solution"]["paths"].dump(-1, ' ', false, json::error_handler_t::replace);
  CHECK(paths_text.size() > 1000);
  // The same numbers (compared below, bit for bit once parsed), in digits
  // never longer than nlohmann::json's.
  const auto at = line.find("\"paths\":[");
  REQUIRE(at != std::string::npos);
  const auto end = line.find("],\"scenario\":", at);
  REQUIRE(end != std::string::npos);
  CHECK(end + 1 - (at + 8) <= paths_text.size());
  json parsed = json::parse(line);
  // Only the clock's readings may differ.
  parsed["stats"] = tree["stats"];
  parsed["solution"]["stats"] = tree["solution"]["stats"];
  CHECK(parsed == tree);
  // A request built in code holds signed integers: 3 was a seed above, -1 is not.
  json negative = request;
  negative["seed"] = -1;
  const json refused = by_tree.handle(negative);
  CHECK(refused["ok"] == false);
  CHECK(refused["error"].get<std::string>().find("$.seed: must be a whole number >= 0") != std::string::npos);
}
