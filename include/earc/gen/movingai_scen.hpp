// MovingAI scenario files (.scen, shared/datasets/movingai/README.md): the
// benchmark's agent lists, whose first N agents are the instance with N
// robots, at the centres of their start and goal cells, heading 0.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "earc/gen/generators.hpp"
#include "earc/gen/movingai.hpp"
#include "earc/scene/scenario.hpp"

namespace earc::gen {

// One agent of a .scen file: cells as the file gives them (row 0 at the top).
struct ScenAgent {
  int start_col = 0, start_row = 0, goal_col = 0, goal_row = 0;
  int line = 0;  // its line in the file, from 1
};

// A parsed .scen file.
struct MovingAiScen {
  std::string file;      // as given; errors name it
  std::string map_file;  // the map column ("empty-16-16.map"), the same on every line
  int width = 0, height = 0;
  std::vector<ScenAgent> agents;  // in file order
};

// Parses the text of a .scen file. Throws InputError(file, "line N", why)
// for a header other than "version 1", or a line that is not nine
// tab-separated fields of the right kinds, or names another map or size.
MovingAiScen parseMovingAiScen(const std::string& text, const std::string& file);
MovingAiScen readMovingAiScen(const std::string& path);

// The README's footprint for a scenario file's robots: a disc of radius 0.3.
MobileFootprint defaultScenFootprint();

struct ScenSettings {
  int robots = 8;  // the first this many agents, 1..1024
  MobileFootprint footprint = defaultScenFootprint();
};

// The instance of the file's first `robots` agents on `map`: robots m0.. at
// cell centres, heading 0. Throws InputError(scen.file, "line N", why) when
// the file does not fit the map, SettingError for a count or footprint that does not.
Scenario scenarioFromScen(const GridMap& map, const MovingAiScen& scen, const ScenSettings& settings);

// Each of the first `robots` agents' moves from start to goal on the
// 4-connected grid of free cells (BFS), -1 where out of reach. Throws
// InputError for another map or fewer agents, SettingError for a bad count.
std::vector<int> scenGridDistances(const GridMap& map, const MovingAiScen& scen, int robots);

// Steps a robot takes to cross one cell at `translation` per step:
// ceil(1 / translation) (20 at the default 0.05).
int stepsPerCell(double translation);

// The sum-of-costs lower bound of the first `robots` agents: each one's
// grid distance times stepsPerCell(translation). Throws as scenGridDistances
// does, and InputError for a goal out of reach.
std::int64_t scenLowerBound(const GridMap& map, const MovingAiScen& scen, int robots, double translation);

}  // namespace earc::gen
