// Each robot's own shortest way from start to goal, ignoring the other
// robots: the lower bound that refinement and the benchmarks divide by.
#pragma once

#include <cstddef>
#include <vector>

#include "earc/scene/robot_model.hpp"
#include "earc/scene/scenario.hpp"

namespace earc {

// Per robot, steps no valid path of its own can undercut: a mobile robot's
// shortest way around the obstacles (straight-line past max_obstacles), an
// arm's straight-line steps; never below the straight line. Thread-safe.
std::vector<std::size_t> ownPathLowerBounds(const Scenario& scenario, const std::vector<const RobotModel*>& models,
                                            std::size_t max_obstacles = 64);

// Per robot, the steps of a straight motion from start to goal. Thread-safe.
std::vector<std::size_t> straightLineBounds(const Scenario& scenario, const std::vector<const RobotModel*>& models);

}  // namespace earc
