// The MovingAI maps of datasets/movingai/, compiled into the library
// (tools/embed_maps.cmake writes the list at build time), so that
// earc-bench's MovingAI suites run from any directory and any install.
#pragma once

#include <string_view>
#include <vector>

namespace earc::gen {

struct EmbeddedMap {
  std::string_view name;  // the file name without ".map", e.g. "den520d"
  std::string_view text;  // the file, unchanged
};

// Every map, in file-name order.
const std::vector<EmbeddedMap>& embeddedMovingAiMaps();

// The map of that name, or nullptr.
const EmbeddedMap* findEmbeddedMovingAiMap(std::string_view name);

}  // namespace earc::gen
