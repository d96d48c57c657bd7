// The MovingAI maps of datasets/movingai/, compiled into the library
// (tools/embed_maps.cmake writes the list at build time), so that
// earc-bench's MovingAI suites run from any directory and any install.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "earc/gen/movingai.hpp"

namespace earc::gen {

struct EmbeddedMap {
  std::string_view name;  // the file name without ".map", e.g. "den520d"
  std::string_view text;  // the file, unchanged
};

// Every map, in file-name order.
const std::vector<EmbeddedMap>& embeddedMovingAiMaps();

// The map of that name, or nullptr.
const EmbeddedMap* findEmbeddedMovingAiMap(std::string_view name);

// The map of that name parsed (errors name it datasets/movingai/NAME.map),
// or nothing when no map of that name is compiled in.
std::optional<GridMap> embeddedMovingAiMap(std::string_view name);

}  // namespace earc::gen
