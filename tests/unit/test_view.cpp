// The plan viewer's page: its embedded sources are current, it is
// self-contained, its data is compact and exact to 4 decimals, and
// mismatched solutions and bad traces are refused with a path and a reason.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "earc/io/json_io.hpp"
#include "earc/validate/scenario_check.hpp"
#include "earc/view/viewer.hpp"
#include "support.hpp"

using earc::test::kData;
using earc::test::readFile;

using earc::InputError;
using nlohmann::json;
namespace view = earc::view;

namespace {

earc::Scenario swapDiscsFromFile() { return earc::loadScenario(kData + "/scenarios/swap-discs.json"); }

json conflictEvent(int id, int a, int b) {
  return {{"type", "conflict"}, {"id", id}, {"robots", {a, b}}, {"t", 3.5}, {"place", {1.0, 2.0}}, {"at_s", 0.01}};
}

json subproblemEvent(int id, int conflict) {
  return {{"type", "subproblem"},
          {"id", id},
          {"conflict", conflict},
          {"robots", {0, 1}},
          {"window", {1, 9}},
          {"region", {{0, 0}, {4, 3}}},
          {"expansions", 1},
          {"merged", 0},
          {"solved_by", "decoupled"},
          {"attempts", {{{"solver", "database"}, {"ok", false}, {"time_s", 0.001}},
                        {{"solver", "decoupled"}, {"ok", true}, {"time_s", 0.0123456789}}}},
          {"length", 12}};
}

json traceDoc(json events) { return {{"format", "earc.trace.v1"}, {"events", std::move(events)}}; }

// The InputError message for a trace, or "" when it is accepted.
std::string traceError(const json& doc) {
  try {
    view::traceFromJson(doc, swapDiscsFromFile(), "t.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("viewer assets embedded in the build match tools/viewer (run tools/viewer/embed.sh)") {
  const std::filesystem::path dir = std::filesystem::path(EARC_SOURCE_DIR) / "tools" / "viewer";
  int checked = 0;
  for (const auto& a : view::viewerAssets()) {
    const bool current = readFile(dir / a.name) == a.text;
    CHECK_MESSAGE(current, "the embedded copy of tools/viewer/", a.name, " is out of date: run tools/viewer/embed.sh");
    ++checked;
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".html" && ext != ".css" && ext != ".js") continue;
    bool embedded = false;
    for (const auto& a : view::viewerAssets()) embedded = embedded || entry.path().filename() == a.name;
    INFO(entry.path().filename().string() << " is in tools/viewer but not embedded (add it to embed.sh)");
    CHECK(embedded);
  }
  CHECK(checked == 6);
}

TEST_CASE("viewer page is self-contained: no external script, style, font or link, and no network allowed") {
  const earc::Scenario sc = swapDiscsFromFile();
  const earc::Solution sol = earc::loadSolution(kData + "/solutions/swap-discs__valid.json", &sc);
  const std::string html = view::viewerHtml(view::viewerData(sc, sol, nullptr));
  for (const char* bad : {"src=", "href=", "http:", "https:", "url(", "@import", "@font-face", "@EARC_"}) {
    INFO(bad);
    CHECK(html.find(bad) == std::string::npos);
  }
  CHECK(html.find("default-src 'none'") != std::string::npos);
  CHECK(html.find("window.earcViewer") != std::string::npos);
  // The page's own scripts never end their element early.
  for (const auto& a : view::viewerAssets())
    if (std::string(a.name).ends_with(".js")) CHECK(a.text.find("</script") == std::string::npos);
}

TEST_CASE("viewer page embeds a robot name with </script> without ending the data element") {
  earc::Scenario sc = swapDiscsFromFile();
  sc.robots[0].name = "</script><script>alert(1)</script>";
  earc::Solution sol;
  sol.scenario = sc.name;
  const std::string html = view::viewerHtml(view::viewerData(sc, sol, nullptr));
  CHECK(html.find("alert(1)</script>") == std::string::npos);
  CHECK(html.find("\\u003c/script>\\u003cscript>alert(1)") != std::string::npos);
}

TEST_CASE("viewer paths are delta-coded integers in 1e-4 units that sum back to the states within half a unit") {
  earc::Path p(3);
  const double states[][3] = {{1.23456, -2.0, 3.14159}, {1.28456, -2.0, -3.1}, {1.28456, -2.0, -3.1}, {0.00004, 7.5, 0}};
  for (const auto& s : states) p.push(s);
  const json enc = view::encodePath(p);
  REQUIRE(enc.size() == 12);
  CHECK(enc[0] == 12346);
  CHECK(enc[3] == 500);   // 1.28456 -> 12846, minus 12346
  CHECK(enc[6] == 0);     // waiting costs one character per number
  long long sum[3] = {0, 0, 0};
  for (std::size_t k = 0; k < enc.size(); ++k) {
    sum[k % 3] += enc[k].get<long long>();
    CHECK(std::abs(static_cast<double>(sum[k % 3]) * view::kStateQuantum - p.raw()[k]) <= 0.5e-4 + 1e-12);
  }
}

TEST_CASE("viewer data holds the makespan, the stats and the scenario without its format tag") {
  const earc::Scenario sc = swapDiscsFromFile();
  const earc::Solution sol = earc::loadSolution(kData + "/solutions/swap-discs__valid.json", &sc);
  const json d = view::viewerData(sc, sol, nullptr);
  CHECK(d["solution"]["makespan"] == sol.makespan());
  CHECK(d["solution"]["paths"].size() == sc.robots.size());
  CHECK(d["scenario"]["robots"].size() == sc.robots.size());
  CHECK(!d["scenario"].contains("format"));
  CHECK(d["trace"].is_null());
}

TEST_CASE("viewer refuses a solution of another scenario, order, robot count or dimension") {
  const earc::Scenario sc = swapDiscsFromFile();
  const earc::Solution good = earc::loadSolution(kData + "/solutions/swap-discs__valid.json", &sc);
  CHECK_NOTHROW(view::checkSolutionMatches(sc, good, "s.json"));

  auto message = [&](const earc::Solution& s) -> std::string {
    try {
      view::checkSolutionMatches(sc, s, "s.json");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  earc::Solution other = good;
  other.scenario = "elsewhere";
  CHECK(message(other).find("s.json: $.scenario: the solution is for scenario \"elsewhere\"") == 0);

  earc::Solution swapped = good;
  std::swap(swapped.paths[0], swapped.paths[1]);
  std::swap(swapped.robot_names[0], swapped.robot_names[1]);
  CHECK(message(swapped).find("$.paths[0].robot: path of") != std::string::npos);

  earc::Solution fewer = good;
  fewer.paths.pop_back();
  fewer.robot_names.pop_back();
  CHECK(message(fewer).find("$.paths: has 1 paths, the scenario has 2 robots") != std::string::npos);

  earc::Solution empty_path = good;
  empty_path.paths[1].clear();
  CHECK(message(empty_path).find("$.paths[1].states: empty path") != std::string::npos);

  earc::Solution solved_no_paths = good;
  solved_no_paths.paths.clear();
  solved_no_paths.robot_names.clear();
  CHECK(message(solved_no_paths).find("solved, but has no paths") != std::string::npos);
  solved_no_paths.solved = false;
  CHECK(message(solved_no_paths).empty());  // unsolved: shown with a banner
}

TEST_CASE("viewer reads a trace: conflicts and subproblems with rounded numbers, unknown events skipped") {
  json events = {conflictEvent(0, 0, 1), subproblemEvent(0, 0), {{"type", "future-kind"}, {"x", 1}}};
  events[1]["entry"] = 42;
  events[1]["attempts"][0]["detail"] = "3 candidates: 3 ends blocked, 0 invalid, 0 crowded; none to repair";
  const json t = view::traceFromJson(traceDoc(events), swapDiscsFromFile(), "t.json");
  REQUIRE(t["conflicts"].size() == 1);
  REQUIRE(t["subproblems"].size() == 1);
  CHECK(t["conflicts"][0]["t"] == 3.5);
  CHECK(t["conflicts"][0]["robots"] == json({0, 1}));
  const json& s = t["subproblems"][0];
  CHECK(s["entry"] == 42);
  CHECK(s["solved_by"] == "decoupled");
  CHECK(s["attempts"][1]["time_s"].get<double>() == doctest::Approx(0.012346).epsilon(1e-12));
  CHECK(s["attempts"][0]["detail"] == "3 candidates: 3 ends blocked, 0 invalid, 0 crowded; none to repair");
  CHECK_FALSE(s["attempts"][1].contains("detail"));
  CHECK(s["window"] == json({1.0, 9.0}));
  CHECK_FALSE(s.contains("merge_cap"));
  CHECK_FALSE(s.contains("ignore_others"));
  events[1]["merge_cap"] = 7;
  events[1]["ignore_others"] = true;
  const json raised = view::traceFromJson(traceDoc(events), swapDiscsFromFile(), "t.json")["subproblems"][0];
  CHECK(raised["merge_cap"] == 7);
  CHECK(raised["ignore_others"] == true);
}

TEST_CASE("viewer refuses a trace with robots the scenario lacks, dangling references or bad fields") {
  CHECK(traceError(traceDoc(json::array())).empty());
  CHECK(traceError({{"format", "earc.trace.v2"}, {"events", json::array()}}).find("$.format") != std::string::npos);
  CHECK(traceError(traceDoc({conflictEvent(0, 0, 7)})).find("$.events[0].robots[1]: robot index 7 does not exist") !=
        std::string::npos);
  CHECK(traceError(traceDoc({conflictEvent(0, 0, 1), conflictEvent(0, 0, 1)})).find("appears twice") !=
        std::string::npos);
  CHECK(traceError(traceDoc({subproblemEvent(0, 3)})).find("$.events[0].conflict: refers to conflict 3") !=
        std::string::npos);
  json backwards = subproblemEvent(0, 0);
  backwards["window"] = {9, 1};
  CHECK(traceError(traceDoc({conflictEvent(0, 0, 1), backwards})).find("$.events[1].window") != std::string::npos);
  json inverted = subproblemEvent(0, 0);
  inverted["region"] = {{4, 3}, {0, 0}};
  CHECK(traceError(traceDoc({conflictEvent(0, 0, 1), inverted})).find("$.events[1].region") != std::string::npos);
  json fractional = conflictEvent(0, 0, 1);
  fractional["id"] = 0.5;
  CHECK(traceError(traceDoc({fractional})).find("$.events[0].id: expected a whole number") != std::string::npos);
  json odd_detail = subproblemEvent(0, 0);
  odd_detail["attempts"][0]["detail"] = 7;
  CHECK(traceError(traceDoc({conflictEvent(0, 0, 1), odd_detail})).find("$.events[1].attempts[0].detail") !=
        std::string::npos);
  json odd_cap = subproblemEvent(0, 0);
  odd_cap["merge_cap"] = "six";
  CHECK(traceError(traceDoc({conflictEvent(0, 0, 1), odd_cap})).find("$.events[1].merge_cap") != std::string::npos);
  json no_place = conflictEvent(0, 0, 1);
  no_place.erase("place");
  CHECK(traceError(traceDoc({no_place})).find("$.events[0]") != std::string::npos);
}
