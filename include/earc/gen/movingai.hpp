// MovingAI grid maps (shared/datasets/movingai/README.md) as continuous
// scenarios: every blocked cell becomes part of an axis-aligned box
// obstacle, and mobile robots get random valid starts and goals.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "earc/gen/generators.hpp"
#include "earc/geometry/shapes.hpp"
#include "earc/scene/scenario.hpp"

namespace earc::gen {

// A parsed .map file. Row 0 is the top row of the file.
struct GridMap {
  std::string name;  // file name without directory and extension
  int width = 0;
  int height = 0;
  std::vector<unsigned char> blocked;  // row-major, 1 = blocked

  bool isBlocked(int col, int row) const {
    return blocked[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) + static_cast<std::size_t>(col)] != 0;
  }
  // The square of cell (col, row): x in [col, col+1], y in [H-1-row, H-row].
  geo::Aabb cellBox(int col, int row) const;
  // True when a disc lies in [0, W] x [0, H] and overlaps no blocked cell.
  bool discFree(geo::Vec2 centre, double radius) const;
};

// Parse the text of a .map file; `file` names it in errors. Throws
// InputError(file, "line N", reason) for anything malformed.
GridMap parseMovingAiMap(const std::string& text, const std::string& file);
GridMap readMovingAiMap(const std::string& path);

// A block of cells: columns [col, col+cols), rows [row, row+rows).
struct CellRect {
  int col = 0;
  int row = 0;
  int cols = 0;
  int rows = 0;
  bool operator==(const CellRect&) const = default;
};

// Blocked cells as few disjoint rectangles, by a greedy sweep; their union
// is exactly the blocked cells.
std::vector<CellRect> mergeBlockedCells(const GridMap& map);

// The box obstacle covering a rectangle of cells.
Obstacle cellRectObstacle(const GridMap& map, const CellRect& r);

struct MovingAiSettings {
  int robots = 8;  // 1..1024
  MobileFootprint footprint;
  std::uint64_t seed = 1;
};

// The map as a scenario: its merged obstacles and robots m0.. with start and
// goal in one free component. Throws SettingError for a robot count out of
// [1, 1024] and CrowdedError when the robots do not fit.
Scenario generateMovingAi(const GridMap& map, const MovingAiSettings& settings);

}  // namespace earc::gen
