// One robot's earliest timing along a given route among the others' fixed
// timed paths: the search behind refinement's shortcuts (refine.cpp).
// Internal to src/planning.
#pragma once

#include <cstddef>
#include <optional>

#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"
#include "refine_index.hpp"

namespace earc::refine {

// Robot r's `path` to step t0, then along `route` (from that state, a step
// apart) waiting where needed, arriving before `before` and able to stay at
// its end until `horizon`; nothing if none within `max_states`. Not thread-safe.
std::optional<Path> retimeAlong(Occupancy& occ, const RobotModel& m, std::size_t r, const Path& path, std::size_t t0,
                                const Path& route, std::size_t before, std::size_t horizon, DeadlinePoll& poll,
                                std::size_t max_states);

}  // namespace earc::refine
