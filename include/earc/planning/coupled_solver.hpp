// Planning in the composite configuration space of a few robots (OMPL
// RRT-Connect on a compound space restricted to a local region), returning
// a time-stamped local solution. Used by ARC's hierarchy, by the coupled
// whole-problem baseline and by the experience database builder.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/subproblem.hpp"
#include "earc/scene/robot_model.hpp"

namespace earc {

struct CoupledSettings {
  double time_limit_s = 1.0;
  bool simplify = true;        // shortcut the composite path before time-stamping
};

struct CoupledQuery {
  std::vector<const RobotModel*> robots;
  std::vector<std::vector<double>> starts;
  std::vector<std::vector<double>> goals;
  std::vector<ConfigBox> region;  // sampling bounds per robot (empty: whole space)
};

// A solution whose paths all have the same length, start at the starts and
// end at the goals, respect the resolution, and are free of obstacles,
// self-collision and contact between the query's robots at every step and
// midpoint; std::nullopt when none was found within the time limit.
// Deterministic for a given seed when the time limit is not what stops it.
std::optional<LocalSolution> solveCoupled(const CollisionWorld& world, const CoupledQuery& query,
                                          const CoupledSettings& settings, std::uint64_t seed);

// Time-stamps a composite waypoint sequence: each segment is split into the
// largest number of steps any robot needs for it, so all robots move and
// arrive together. waypoints[w][r] is robot r's configuration at waypoint w.
LocalSolution timeStampComposite(const std::vector<const RobotModel*>& robots,
                                 const std::vector<std::vector<std::vector<double>>>& waypoints);

}  // namespace earc
