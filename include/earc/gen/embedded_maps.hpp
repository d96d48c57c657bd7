// The MovingAI maps and scenario files of datasets/movingai/, compiled
// into the library (tools/embed_maps.cmake writes the lists at build
// time), so that earc-bench's MovingAI and crowd suites run from any
// directory and any install.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "earc/gen/movingai.hpp"
#include "earc/gen/movingai_scen.hpp"

namespace earc::gen {

struct EmbeddedMap {
  std::string_view name;  // the file name without ".map" (".scen"), e.g. "den520d"
  std::string_view text;  // the file, unchanged
};

// Every map, in file-name order.
const std::vector<EmbeddedMap>& embeddedMovingAiMaps();

// The map of that name, or nullptr.
const EmbeddedMap* findEmbeddedMovingAiMap(std::string_view name);

// The map of that name parsed (errors name it datasets/movingai/NAME.map),
// or nothing when no map of that name is compiled in.
std::optional<GridMap> embeddedMovingAiMap(std::string_view name);

// Every scenario file (.scen), in file-name order.
const std::vector<EmbeddedMap>& embeddedMovingAiScens();

// The scenario file of that name ("empty-16-16-random-1"), or nullptr.
const EmbeddedMap* findEmbeddedMovingAiScen(std::string_view name);

// That scenario file parsed (errors name it datasets/movingai/NAME.scen),
// or nothing when none of that name is compiled in.
std::optional<MovingAiScen> embeddedMovingAiScen(std::string_view name);

}  // namespace earc::gen
