#include "earc/gen/movingai.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/embedded_maps.hpp"
#include "earc/gen/placement.hpp"
#include "earc/gen/random.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/util/format.hpp"

namespace earc::gen {

namespace {

// Largest map side accepted: den520d is 256, the largest benchmark maps ~1500.
constexpr int kMaxMapSide = 8192;
constexpr int kMaxPlacementTries = 20;

// Terrain characters of the format: '.' and 'G' free; the rest blocked.
bool terrainBlocked(char c, bool& known) {
  known = true;
  switch (c) {
    case '.': case 'G': return false;
    case '@': case 'O': case 'T': case 'S': case 'W': return true;
    default: known = false; return true;
  }
}

// A byte of the file as a message shows it: 'x' when it is printable
// ASCII, else its value, "byte 0x00". Never the byte itself: a NUL ends
// the message (what() is a C string) and a control character splits it or
// drives the terminal; '?', how printableText shows them, is a terrain
// character that is unknown too.
std::string mapByteText(char c) {
  const auto b = static_cast<unsigned char>(c);
  if (b >= 0x20 && b < 0x7F) return "'" + std::string(1, c) + "'";
  char hex[16];
  std::snprintf(hex, sizeof hex, "byte 0x%02X", b);
  return hex;
}

// "height 32" -> 32; throws for anything else.
int headerNumber(const std::string& line, const std::string& key, const std::string& file, int line_no) {
  std::istringstream in(line);
  std::string k, extra;
  long long v = 0;
  if (!(in >> k >> v) || k != key || (in >> extra))
    throw InputError(file, "line " + std::to_string(line_no),
                     "expected '" + key + " <number>', got '" + printableText(line, 80) + "'");
  if (v < 1 || v > kMaxMapSide)
    throw InputError(file, "line " + std::to_string(line_no),
                     key + " must be between 1 and " + std::to_string(kMaxMapSide) + ", got " + std::to_string(v));
  return static_cast<int>(v);
}

}  // namespace

geo::Aabb GridMap::cellBox(int col, int row) const {
  return {{static_cast<double>(col), static_cast<double>(height - 1 - row)},
          {static_cast<double>(col + 1), static_cast<double>(height - row)}};
}

bool GridMap::discFree(geo::Vec2 c, double r) const {
  if (c.x - r < 0.0 || c.y - r < 0.0 || c.x + r > width || c.y + r > height) return false;
  const int col_lo = std::max(0, static_cast<int>(std::floor(c.x - r)));
  const int col_hi = std::min(width - 1, static_cast<int>(std::floor(c.x + r)));
  const int row_lo = std::max(0, height - 1 - static_cast<int>(std::floor(c.y + r)));
  const int row_hi = std::min(height - 1, height - 1 - static_cast<int>(std::floor(c.y - r)));
  for (int row = row_lo; row <= row_hi; ++row)
    for (int col = col_lo; col <= col_hi; ++col) {
      if (!isBlocked(col, row)) continue;
      const geo::Aabb b = cellBox(col, row);
      const double dx = std::max({b.lo.x - c.x, 0.0, c.x - b.hi.x});
      const double dy = std::max({b.lo.y - c.y, 0.0, c.y - b.hi.y});
      if (dx * dx + dy * dy < r * r) return false;
    }
  return true;
}

GridMap parseMovingAiMap(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  auto next = [&]() -> bool {
    if (!std::getline(in, line)) return false;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  };
  auto at = [&]() { return "line " + std::to_string(line_no); };

  GridMap map;
  map.name = std::filesystem::path(file).stem().string();
  // Lines count from 1: an empty file lacks line 1 (it said "line 0").
  if (!next()) throw InputError(file, "line 1", "the file is empty: expected the header 'type octile'");
  if (line.rfind("type ", 0) != 0)
    throw InputError(file, at(), "expected the header 'type octile' (is this a MovingAI .map file?)");
  // The cells of the other types (a hex map's rows are offset) are not
  // squares: read as octile, the obstacles would be in the wrong places.
  if (line != "type octile")
    throw InputError(file, at(), "expected the header 'type octile', got '" + printableText(line, 80) +
                                     "': only octile maps are read");
  if (!next()) throw InputError(file, at(), "missing 'height' line");
  map.height = headerNumber(line, "height", file, line_no);
  if (!next()) throw InputError(file, at(), "missing 'width' line");
  map.width = headerNumber(line, "width", file, line_no);
  if (!next() || line != "map") throw InputError(file, at(), "expected 'map' after the header");

  map.blocked.resize(static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height));
  for (int row = 0; row < map.height; ++row) {
    if (!next())
      throw InputError(file, at(), "the map has " + std::to_string(row) + " rows, the header says " +
                                       std::to_string(map.height));
    if (static_cast<int>(line.size()) != map.width)
      throw InputError(file, at(), "row " + std::to_string(row) + " has " + std::to_string(line.size()) +
                                       " characters, the header says width " + std::to_string(map.width));
    for (int col = 0; col < map.width; ++col) {
      bool known = false;
      const bool b = terrainBlocked(line[static_cast<std::size_t>(col)], known);
      if (!known)
        throw InputError(file, at(), "column " + std::to_string(col + 1) + ": unknown terrain character " +
                                         mapByteText(line[static_cast<std::size_t>(col)]));
      map.blocked[static_cast<std::size_t>(row) * static_cast<std::size_t>(map.width) + static_cast<std::size_t>(col)] = b;
    }
  }
  while (next())
    if (!line.empty())
      throw InputError(file, at(), "text after the last of the " + std::to_string(map.height) + " map rows");
  return map;
}

GridMap readMovingAiMap(const std::string& path) { return parseMovingAiMap(readTextFile(path), path); }

const EmbeddedMap* findEmbeddedMovingAiMap(std::string_view name) {
  for (const EmbeddedMap& m : embeddedMovingAiMaps())
    if (m.name == name) return &m;
  return nullptr;
}

std::optional<GridMap> embeddedMovingAiMap(std::string_view name) {
  const EmbeddedMap* m = findEmbeddedMovingAiMap(name);
  if (!m) return std::nullopt;
  return parseMovingAiMap(std::string(m->text), "datasets/movingai/" + std::string(name) + ".map");
}

// Blocked cells as few rectangles as a greedy sweep finds: take the first
// uncovered blocked cell in reading order, extend it right along the row,
// then down while the whole run below is blocked and uncovered. The
// rectangles are disjoint and their union is exactly the blocked cells.
std::vector<CellRect> mergeBlockedCells(const GridMap& map) {
  std::vector<unsigned char> covered(map.blocked.size(), 0);
  auto index = [&](int col, int row) {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(map.width) + static_cast<std::size_t>(col);
  };
  auto open = [&](int col, int row) { return map.isBlocked(col, row) && !covered[index(col, row)]; };
  std::vector<CellRect> rects;
  for (int row = 0; row < map.height; ++row)
    for (int col = 0; col < map.width; ++col) {
      if (!open(col, row)) continue;
      CellRect r{col, row, 1, 1};
      while (r.col + r.cols < map.width && open(r.col + r.cols, row)) ++r.cols;
      auto run_open = [&](int rr) {
        for (int c = r.col; c < r.col + r.cols; ++c)
          if (!open(c, rr)) return false;
        return true;
      };
      while (r.row + r.rows < map.height && run_open(r.row + r.rows)) ++r.rows;
      for (int rr = r.row; rr < r.row + r.rows; ++rr)
        for (int c = r.col; c < r.col + r.cols; ++c) covered[index(c, rr)] = 1;
      rects.push_back(r);
    }
  return rects;
}

Obstacle cellRectObstacle(const GridMap& map, const CellRect& r) {
  Obstacle o;
  o.type = Obstacle::Type::Box;
  o.center = {r.col + 0.5 * r.cols, map.height - r.row - 0.5 * r.rows};
  o.size = {static_cast<double>(r.cols), static_cast<double>(r.rows)};
  return o;
}

Scenario generateMovingAi(const GridMap& map, const MovingAiSettings& settings) {
  if (settings.robots < 1 || settings.robots > 1024)
    throw SettingError("robots", "must be in [1, 1024], got " + std::to_string(settings.robots));
  Scenario s;
  s.name = "movingai-" + map.name + footprintTag(settings.footprint) + "-" + std::to_string(settings.robots) + "-s" +
           std::to_string(settings.seed);
  s.workspace = {{0.0, 0.0}, {static_cast<double>(map.width), static_cast<double>(map.height)}};
  for (const CellRect& r : mergeBlockedCells(map)) s.obstacles.push_back(cellRectObstacle(map, r));

  const MobileFootprint& f = settings.footprint;
  // A 1e-300 radius would pass placement; a radius wider than the map is
  // named as itself, not as too many robots.
  requireFootprint(f, std::min(map.width, map.height),
                   "the " + std::to_string(map.width) + " x " + std::to_string(map.height) + " map");
  for (int i = 0; i < settings.robots; ++i) s.robots.push_back(mobileRobot(i, f));
  const CollisionWorld world(s);
  // The map's own cell test is exact and much faster than the world's.
  auto disc_free = [&map](geo::Vec2 c, double r) { return map.discFree(c, r); };
  Random rng(settings.seed);
  // The obstacles are the map's: a failed placement only draws again.
  for (int attempt = 0; attempt < kMaxPlacementTries; ++attempt)
    if (placeMobileRobots(s, world, disc_free, rng)) return s;
  throw CrowdedError("could not place " + std::to_string(settings.robots) + " robots on map " + map.name +
                           ": use fewer robots or a smaller footprint");
}

}  // namespace earc::gen
