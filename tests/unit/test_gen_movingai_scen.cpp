// MovingAI scenario files: parsing, the instance of the first N agents,
// every refusal naming the line, and the grid lower bound.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "earc/gen/embedded_maps.hpp"
#include "earc/gen/movingai_scen.hpp"
#include "earc/io/input_error.hpp"

using namespace earc;
using namespace earc::gen;

namespace {

// A 4 x 3 map named "tiny" with one blocked cell, (column 1, row 1):
//   ....
//   .@..
//   ....
GridMap tinyMap() {
  return parseMovingAiMap("type octile\nheight 3\nwidth 4\nmap\n....\n.@..\n....\n", "maps/tiny.map");
}

std::string agentLine(int sc, int sr, int gc, int gr, const std::string& map = "tiny.map", int w = 4, int h = 3) {
  return "0\t" + map + "\t" + std::to_string(w) + "\t" + std::to_string(h) + "\t" + std::to_string(sc) + "\t" +
         std::to_string(sr) + "\t" + std::to_string(gc) + "\t" + std::to_string(gr) + "\t0\n";
}

// Three agents: (0,0)->(3,2), (2,1)->(0,1), (3,0)->(1,2).
std::string goodScen() { return "version 1\n" + agentLine(0, 0, 3, 2) + agentLine(2, 1, 0, 1) + agentLine(3, 0, 1, 2); }

// The error's "where" and reason, from parsing and then instancing.
InputError errorOf(const std::string& text, int robots = 2) {
  try {
    const MovingAiScen scen = parseMovingAiScen(text, "a.scen");
    ScenSettings s;
    s.robots = robots;
    scenarioFromScen(tinyMap(), scen, s);
  } catch (const InputError& e) {
    return e;
  }
  FAIL("no InputError");
  return InputError("", "", "");
}

}  // namespace

TEST_CASE("a .scen file's first N agents become robots at cell centres, discs of 0.3 by default") {
  const MovingAiScen scen = parseMovingAiScen(goodScen(), "dir/tiny-random-1.scen");
  REQUIRE(scen.agents.size() == 3);
  CHECK(scen.map_file == "tiny.map");
  CHECK(scen.agents[1].line == 3);
  ScenSettings s;
  s.robots = 2;
  const Scenario sc = scenarioFromScen(tinyMap(), scen, s);
  CHECK(sc.name == "movingai-tiny-random-1-disc-2");
  REQUIRE(sc.robots.size() == 2);
  CHECK(sc.robots[0].shape == MobileShape::Disc);
  CHECK(sc.robots[0].radius == doctest::Approx(0.3));
  // (col + 0.5, H - 1 - row + 0.5), heading 0.
  CHECK(sc.robots[0].start == std::vector<double>{0.5, 2.5, 0.0});
  CHECK(sc.robots[0].goal == std::vector<double>{3.5, 0.5, 0.0});
  CHECK(sc.robots[1].start == std::vector<double>{2.5, 1.5, 0.0});
  CHECK(sc.workspace.hi.x == 4.0);
  CHECK(sc.workspace.hi.y == 3.0);
  CHECK(sc.obstacles.size() == 1);
  // A box footprint, when asked for.
  s.footprint = MobileFootprint{};
  CHECK(scenarioFromScen(tinyMap(), scen, s).robots[0].shape == MobileShape::Box);
}

TEST_CASE("the grid lower bound: BFS moves times ceil(1 / translation) steps") {
  const MovingAiScen scen = parseMovingAiScen(goodScen(), "a.scen");
  // (0,0)->(3,2): 5 moves. (2,1)->(0,1): around the blocked (1,1), 4 moves.
  // (3,0)->(1,2): 4 moves.
  CHECK(scenGridDistances(tinyMap(), scen, 3) == std::vector<int>{5, 4, 4});
  CHECK(stepsPerCell(0.05) == 20);
  CHECK(stepsPerCell(0.3) == 4);
  CHECK(scenLowerBound(tinyMap(), scen, 2, 0.05) == (5 + 4) * 20);
  CHECK(scenLowerBound(tinyMap(), scen, 3, 0.05) == 13 * 20);
}

TEST_CASE("a .scen file that does not fit the map is refused naming the file and the line") {
  struct Case {
    std::string text;
    int robots;
    std::string where, reason;
  };
  const std::string hdr = "version 1\n";
  const std::vector<Case> cases = {
      {"version 2\n" + agentLine(0, 0, 3, 2), 1, "line 1", "expected the header 'version 1', got 'version 2'"},
      {"", 1, "line 1", "the file is empty"},
      {hdr + "0\ttiny.map\t4\t3\t0\t0\t3\n", 1, "line 2", "expected 9 tab-separated fields"},
      {hdr + agentLine(0, 0, 3, 2) + "0\ttiny.map\t4\t3\tx\t0\t3\t2\t0\n", 1, "line 3", "start column: expected a whole number"},
      {hdr + agentLine(0, 0, 3, 2) + "0\ttiny.map\t4\t3\t0\t0\t3\t2\tfar\n", 1, "line 3", "optimal length"},
      {hdr + agentLine(0, 0, 4, 2), 1, "line 2", "goal column 4 is outside the map's 4 columns"},
      {hdr + agentLine(0, 3, 0, 2), 1, "line 2", "start row 3 is outside the map's 3 rows"},
      {hdr + agentLine(0, 0, 3, 2) + agentLine(1, 1, 3, 1), 1, "line 3", "start cell (column 1, row 1) is blocked on map tiny"},
      {hdr + agentLine(0, 0, 3, 2) + agentLine(0, 2, 1, 1), 1, "line 3", "goal cell (column 1, row 1) is blocked"},
      {hdr + agentLine(0, 0, 3, 2), 2, "", "the file has 1 agents, fewer than the 2 robots asked for"},
      {hdr + agentLine(0, 0, 3, 2) + agentLine(0, 0, 2, 2), 2, "line 3", "start cell (column 0, row 0) is also the start of line 2"},
      {hdr + agentLine(0, 0, 3, 2) + agentLine(1, 0, 3, 2), 2, "line 3", "goal cell (column 3, row 2) is also the goal of line 2"},
      {hdr + agentLine(0, 0, 3, 2, "other.map"), 1, "line 2", "its agents are on map other.map of 4 x 3 cells, not on tiny"},
      {hdr + agentLine(0, 0, 3, 2, "tiny.map", 5, 3), 1, "line 2", "not on tiny of 4 x 3"},
      {hdr + agentLine(0, 0, 3, 2) + agentLine(0, 1, 3, 1, "tiny.map", 5, 3), 1, "line 3", "where line 2 says tiny.map of 4 x 3"},
      {hdr + agentLine(0, 0, 3, 2) + "\n" + agentLine(1, 0, 2, 2), 1, "line 3", "a blank line between agents"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.text);
    const InputError e = errorOf(c.text, c.robots);
    CHECK(e.file() == "a.scen");
    CHECK(e.where() == c.where);
    CHECK(e.reason().find(c.reason) != std::string::npos);
    CHECK(std::string(e.what()).find('\n') == std::string::npos);
  }
  // Blank lines may end a file; CRLF line ends are read.
  CHECK(parseMovingAiScen(goodScen() + "\n\n", "a.scen").agents.size() == 3);
  CHECK(parseMovingAiScen("version 1\r\n" + agentLine(0, 0, 3, 2), "a.scen").agents.size() == 1);
}

TEST_CASE("a goal out of reach and a footprint larger than a cell are refused") {
  const GridMap walled =
      parseMovingAiMap("type octile\nheight 2\nwidth 3\nmap\n.@.\n.@.\n", "walled.map");
  const MovingAiScen scen = parseMovingAiScen("version 1\n" + agentLine(0, 0, 2, 0, "walled.map", 3, 2), "w.scen");
  ScenSettings s;
  s.robots = 1;
  try {
    scenarioFromScen(walled, scen, s);
    FAIL("accepted");
  } catch (const InputError& e) {
    CHECK(e.where() == "line 2");
    CHECK(e.reason().find("cannot be reached") != std::string::npos);
  }
  CHECK(scenGridDistances(walled, scen, 1) == std::vector<int>{-1});
  CHECK_THROWS_AS(scenLowerBound(walled, scen, 1, 0.05), InputError);
  s.footprint.radius = 0.6;
  CHECK_THROWS_AS(scenarioFromScen(tinyMap(), parseMovingAiScen(goodScen(), "a.scen"), s), SettingError);
  s.footprint.radius = 0.3;
  s.robots = 0;
  CHECK_THROWS_AS(scenarioFromScen(tinyMap(), parseMovingAiScen(goodScen(), "a.scen"), s), SettingError);
}

TEST_CASE("the benchmark's scenario files are compiled in and fit their maps") {
  for (const char* name : {"empty-16-16", "random-32-32-20", "room-32-32-4", "warehouse-10-20-10-2-1"}) {
    CAPTURE(name);
    const auto map = embeddedMovingAiMap(name);
    const auto scen = embeddedMovingAiScen(std::string(name) + "-random-1");
    REQUIRE(map);
    REQUIRE(scen);
    ScenSettings s;
    s.robots = static_cast<int>(scen->agents.size());
    CHECK(scenarioFromScen(*map, *scen, s).robots.size() == scen->agents.size());
    CHECK(scenLowerBound(*map, *scen, s.robots, 0.05) > 0);
  }
  CHECK_FALSE(embeddedMovingAiScen("nowhere-random-1"));
}
