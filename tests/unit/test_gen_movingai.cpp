// MovingAI maps: parsing, exact rectangle merge, and scenarios on them.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "earc/gen/movingai.hpp"
#include "earc/gen/random.hpp"
#include "earc/io/json_io.hpp"
#include "earc/validate/scenario_check.hpp"

using namespace earc;
using namespace earc::gen;

namespace {

const std::string kMapDir = std::string(EARC_SOURCE_DIR) + "/datasets/movingai/";

std::string mapText(int width, const std::vector<std::string>& rows) {
  std::string t = "type octile\nheight " + std::to_string(rows.size()) + "\nwidth " + std::to_string(width) + "\nmap\n";
  for (const auto& r : rows) t += r + "\n";
  return t;
}

// Each blocked cell covered by exactly one rectangle, no free cell by any.
void checkExactCover(const GridMap& map) {
  const std::vector<CellRect> rects = mergeBlockedCells(map);
  std::vector<int> cover(map.blocked.size(), 0);
  for (const auto& r : rects) {
    REQUIRE(r.cols >= 1);
    REQUIRE(r.rows >= 1);
    REQUIRE(r.col + r.cols <= map.width);
    REQUIRE(r.row + r.rows <= map.height);
    for (int row = r.row; row < r.row + r.rows; ++row)
      for (int col = r.col; col < r.col + r.cols; ++col) ++cover[static_cast<std::size_t>(row * map.width + col)];
  }
  int wrong = 0;
  for (int row = 0; row < map.height; ++row)
    for (int col = 0; col < map.width; ++col)
      wrong += cover[static_cast<std::size_t>(row * map.width + col)] != (map.isBlocked(col, row) ? 1 : 0);
  CHECK(wrong == 0);
}

std::string whereOfParseError(const std::string& text) {
  try {
    parseMovingAiMap(text, "bad.map");
  } catch (const InputError& e) {
    CHECK(e.file() == "bad.map");
    return e.where();
  }
  FAIL("no InputError");
  return {};
}

}  // namespace

TEST_CASE("a .map file parses into free and blocked cells with row 0 at the top") {
  const GridMap m = parseMovingAiMap(mapText(3, {"@..", ".GT", "OSW"}), "dir/tiny.map");
  CHECK(m.name == "tiny");
  CHECK(m.width == 3);
  CHECK(m.height == 3);
  CHECK(m.isBlocked(0, 0));
  CHECK_FALSE(m.isBlocked(1, 0));
  CHECK_FALSE(m.isBlocked(1, 1));  // G is free
  CHECK(m.isBlocked(2, 1));
  for (int c = 0; c < 3; ++c) CHECK(m.isBlocked(c, 2));
}

TEST_CASE("blocked cell (col, row) becomes the box from (col, H-1-row) to (col+1, H-row)") {
  const GridMap m = parseMovingAiMap(mapText(4, {"....", "..@.", "...."}), "m.map");
  const auto rects = mergeBlockedCells(m);
  REQUIRE(rects.size() == 1);
  CHECK(rects[0] == CellRect{2, 1, 1, 1});
  const geo::Aabb b = geo::bounds(cellRectObstacle(m, rects[0]).body());
  CHECK(b.lo.x == doctest::Approx(2.0));
  CHECK(b.hi.x == doctest::Approx(3.0));
  CHECK(b.lo.y == doctest::Approx(1.0));  // H - 1 - row = 3 - 1 - 1
  CHECK(b.hi.y == doctest::Approx(2.0));
}

TEST_CASE("merged rectangles cover exactly the blocked cells of random maps") {
  Random rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const int w = 1 + static_cast<int>(rng.uniform(0, 20)), h = 1 + static_cast<int>(rng.uniform(0, 20));
    const double density = rng.uniform();
    std::vector<std::string> rows;
    for (int r = 0; r < h; ++r) {
      std::string row;
      for (int c = 0; c < w; ++c) row += rng.uniform() < density ? '@' : '.';
      rows.push_back(row);
    }
    CAPTURE(trial);
    checkExactCover(parseMovingAiMap(mapText(w, rows), "random.map"));
  }
}

TEST_CASE("merged rectangles cover exactly the blocked cells of the benchmark maps") {
  for (std::string name : {"random-32-32-10.map", "den520d.map"}) {
    CAPTURE(name);
    checkExactCover(readMovingAiMap(kMapDir + name));
  }
}

TEST_CASE("den520d's blocked cells merge into a few hundred boxes, not tens of thousands") {
  const GridMap m = readMovingAiMap(kMapDir + "den520d.map");
  std::size_t blocked = 0;
  for (auto b : m.blocked) blocked += b;
  const std::size_t boxes = mergeBlockedCells(m).size();
  CHECK(blocked > 30000);
  CHECK(boxes < 1000);
}

TEST_CASE("a fully blocked map merges into one rectangle") {
  const auto rects = mergeBlockedCells(parseMovingAiMap(mapText(3, {"@@@", "TTT"}), "full.map"));
  REQUIRE(rects.size() == 1);
  CHECK(rects[0] == CellRect{0, 0, 3, 2});
}

TEST_CASE("malformed map files name the line and the reason") {
  CHECK(whereOfParseError("type octile\nheight x\nwidth 3\nmap\n") == "line 2");
  CHECK(whereOfParseError("hello\n") == "line 1");
  CHECK(whereOfParseError("") == "line 1");  // lines count from 1 (it said "line 0")
  // Only octile maps: the other types' cells are not squares.
  CHECK(whereOfParseError(mapText(1, {"."}).replace(0, 11, "type hex")) == "line 1");
  CHECK(whereOfParseError(mapText(1, {"."}).replace(0, 11, "type whatever")) == "line 1");
  CHECK_NOTHROW(parseMovingAiMap(mapText(1, {"."}), "octile.map"));
  CHECK(whereOfParseError("type octile\nheight 2\nwidth 3\nnot map\n") == "line 4");
  CHECK(whereOfParseError(mapText(3, {"...", ".x."})) == "line 6");  // unknown terrain
  CHECK(whereOfParseError(mapText(3, {"...", ".."})) == "line 6");   // short row
  CHECK(whereOfParseError("type octile\nheight 3\nwidth 2\nmap\n..\n..\n") == "line 6");  // missing row
  CHECK(whereOfParseError(mapText(2, {"..", ".."}) + "..\n") == "line 7");  // extra row
  CHECK(whereOfParseError("type octile\nheight 0\nwidth 2\nmap\n") == "line 2");
}

TEST_CASE("a NUL or other unprintable byte in a map is named by line, column and value, in a whole message") {
  // what() as the tools print it: a C string, up to the first NUL.
  auto message = [](const std::string& text) -> std::string {
    try {
      parseMovingAiMap(text, "bad.map");
    } catch (const InputError& e) {
      return e.what();
    }
    FAIL("no InputError");
    return {};
  };
  const std::string nul(1, '\0');
  CHECK(message(mapText(3, {"...", "." + nul + "."})) == "bad.map: line 6: column 2: unknown terrain character byte 0x00");
  CHECK(message(mapText(3, {"..\x1b", "..."})) == "bad.map: line 5: column 3: unknown terrain character byte 0x1B");
  CHECK(message(mapText(3, {"\xff..", "..."})) == "bad.map: line 5: column 1: unknown terrain character byte 0xFF");
  CHECK(message(mapText(3, {"...", ".?."})) == "bad.map: line 6: column 2: unknown terrain character '?'");
  // A header line is quoted printably (printableText: '?' for the NUL).
  CHECK(message("type octile\nheight 2" + nul + "x\nwidth 3\nmap\n") ==
        "bad.map: line 2: expected 'height <number>', got 'height 2?x'");
}

TEST_CASE("reading a missing map file is an InputError naming the file") {
  CHECK_THROWS_AS(readMovingAiMap(kMapDir + "no-such.map"), InputError);
}

TEST_CASE("CRLF map files parse like LF ones") {
  std::string t = mapText(2, {".@", ".."});
  std::string crlf;
  for (char c : t) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const GridMap a = parseMovingAiMap(t, "a.map"), b = parseMovingAiMap(crlf, "b.map");
  CHECK(a.blocked == b.blocked);
}

TEST_CASE("a disc is free on the map exactly when it stays in bounds and off blocked cells") {
  const GridMap m = parseMovingAiMap(mapText(3, {"...", ".@.", "..."}), "m.map");
  CHECK(m.discFree({0.5, 0.5}, 0.4));
  CHECK_FALSE(m.discFree({1.5, 1.5}, 0.1));   // inside the blocked cell
  CHECK_FALSE(m.discFree({0.5, 1.5}, 0.6));   // reaches into it
  CHECK(m.discFree({0.5, 1.5}, 0.5));         // just touches its side
  CHECK_FALSE(m.discFree({0.3, 0.5}, 0.4));   // leaves the map
  CHECK_FALSE(m.discFree({0.8, 0.8}, 0.3));   // near the cell's corner (1, 1)
}

TEST_CASE("MovingAI scenarios are valid, deterministic per seed, on the map's workspace") {
  const GridMap m = readMovingAiMap(kMapDir + "random-32-32-10.map");
  MovingAiSettings s;
  s.robots = 16;
  s.seed = 2;
  const Scenario a = generateMovingAi(m, s), b = generateMovingAi(m, s);
  CHECK(scenarioToJson(a).dump() == scenarioToJson(b).dump());
  s.seed = 3;
  CHECK(scenarioToJson(a).dump() != scenarioToJson(generateMovingAi(m, s)).dump());
  CHECK(a.name == "movingai-random-32-32-10-16-s2");
  s.footprint.shape = MobileShape::Disc;
  s.footprint.radius = 0.45;
  CHECK(generateMovingAi(m, s).name == "movingai-random-32-32-10-disc-r0.45-16-s3");
  CHECK(a.workspace.hi.x == 32.0);
  CHECK(a.workspace.hi.y == 32.0);
  CHECK(a.obstacles.size() == mergeBlockedCells(m).size());
  CHECK_NOTHROW(checkScenarioGeometry(a, a.name));
  s.footprint.shape = MobileShape::Disc;
  const Scenario d = generateMovingAi(m, s);
  CHECK_NOTHROW(checkScenarioGeometry(d, d.name));
}

TEST_CASE("on a map split by a wall each robot's start and goal lie on one side") {
  std::vector<std::string> rows(12, std::string(5, '.') + "@" + std::string(6, '.'));
  const GridMap m = parseMovingAiMap(mapText(12, rows), "split.map");
  MovingAiSettings s;
  s.robots = 10;
  s.seed = 5;
  const Scenario sc = generateMovingAi(m, s);
  for (const auto& r : sc.robots) CHECK((r.start[0] < 5) == (r.goal[0] < 5));
}
