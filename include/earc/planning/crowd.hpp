// Crowds of mobile robots planned together: the crowd roadmap, LaCAM on it,
// and the configurations turned into time-stamped paths at the scenario's
// resolution. Used as a whole-problem method and by ARC for a jam.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/crowd_roadmap.hpp"
#include "earc/planning/plan_stats.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

struct CrowdOutcome {
  std::optional<std::vector<Path>> paths;  // one per group robot, from start to goal
  LacamStats stats;
  std::string why;      // why not solved
  bool timed_out = false;
};

// What planCrowd does after its first plan.
struct CrowdOptions {
  // Each robot that waits or detours is replanned once alone on the
  // roadmap, as part of the first plan (ARC's jams).
  bool polish = false;
  // Then the plan is shortened on the roadmap for most of refine_s seconds
  // (with diagonal steps on a grid map's cells), within refine_deadline if
  // given, else the plan's deadline.
  double refine_s = 0.0;
  const Deadline* refine_deadline = nullptr;
};

// Plans robots[i] (indices into models, all mobile) from starts[i] to
// goals[i] together, ignoring every other robot, within `deadline`, then
// as `options` say. Throws std::invalid_argument for an arm.
CrowdOutcome planCrowd(const CollisionWorld& world, const std::vector<const RobotModel*>& models,
                       const std::vector<int>& robots, const std::vector<std::vector<double>>& starts,
                       const std::vector<std::vector<double>>& goals, const Deadline& deadline, std::uint64_t seed,
                       const CrowdOptions& options = {});

// Time-stamped paths of LaCAM's configurations, `per_step` time steps per
// configuration step, headings turned on the lattice (crowd.cpp says how).
// Nothing when a robot cannot turn anywhere. Thread-safe.
std::optional<std::vector<Path>> crowdPaths(const CrowdRoadmap& roadmap, std::vector<std::vector<int>> configs,
                                            int per_step, const std::vector<std::vector<double>>& starts,
                                            const std::vector<std::vector<double>>& goals);


// The robots ARC hands a jam to: `robots` (the conflict's group), then
// `previous` (the last group handed over), then the others by how near their
// paths pass `place`, up to `size` in all (ascending indices).
std::vector<int> jamGroup(const std::vector<Path>& paths, std::vector<int> robots, const std::vector<int>& previous,
                          geo::Vec2 place, std::size_t size);

}  // namespace earc
