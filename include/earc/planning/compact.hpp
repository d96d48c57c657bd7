// Plan compaction (`earc-plan plan --compact`): every robot retimed along
// its own path, leaving out the waits it does not need, with the other
// robots' paths held as they are. Not part of ARC or E-ARC as the paper
// describes them; a step after any method's plan, off unless asked for.
//
// A robot keeps its geometric route (its path with repeated states left
// out) and so every motion it makes, which are valid against the
// obstacles already; only when it makes them changes. The new timing is
// checked against every other robot at every step and midpoint (the
// instants that conflicts and the contract use), and the robot must be
// able to stay at its goal from its arrival on. So a valid plan stays
// valid, and no robot arrives later than it did.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

struct CompactReport {
  int passes = 0;               // passes over the robots that were started
  int robots_retimed = 0;       // retimings kept, over all passes
  std::int64_t steps_saved = 0; // summed over robots (the sum of costs falls by as much)
  int robots_shortcut = 0;      // robots whose route a shortcut made shorter
  std::size_t states = 0;       // (route position, step) pairs the searches tried
  bool interrupted = false;     // the deadline ended it; the paths are valid as they stand
};

// Retimes `paths` (one per robot, each ending at its goal, trailing waits
// dropped) in place, leaving out waits (and, with a world, slow straight
// motions) that no other robot needs, until a pass saves nothing.
CompactReport compactPlan(const std::vector<const RobotModel*>& models, std::vector<Path>& paths,
                          const CollisionWorld* world, const Deadline& deadline, int max_passes = 4,
                          std::size_t states_per_position = 64);

// As compactPlan, but retimes only the robots listed in `which` (indices
// into `paths`, each a path of its own); the others are held as they are.
CompactReport compactRobots(const std::vector<const RobotModel*>& models, std::vector<Path>& paths,
                            const std::vector<std::size_t>& which, const CollisionWorld* world,
                            const Deadline& deadline, int max_passes = 4, std::size_t states_per_position = 64);

// Of the robots in `which` at least a quarter later than their straight-line
// arrival, the `robots` furthest behind get `tries` stretches of their route,
// drawn from `seed`, made straight motions where the world allows and it arrives earlier.
CompactReport shortcutRobots(const std::vector<const RobotModel*>& models, std::vector<Path>& paths,
                             const std::vector<std::size_t>& which, const CollisionWorld& world,
                             const Deadline& deadline, std::size_t robots, int tries, std::uint64_t seed,
                             std::size_t states_per_position = 8);

// The path without repeated states (consecutive equal ones kept once).
Path routeOf(const Path& path);

// `route` with each run of states along one straight motion, slower than the
// resolution allows, made again in the fewest steps where the world allows;
// nothing when no run got shorter or the deadline expired. Thread-safe.
std::optional<Path> routeAtFullSpeed(const RobotModel& model, const Path& route, const CollisionWorld& world,
                                     const Deadline& deadline);

// The box that the model's bounding disc stays in over states [from, to) of
// the path (to clipped to its size). Thread-safe.
geo::Aabb pathReach(const RobotModel& model, const Path& path, std::size_t from = 0,
                    std::size_t to = std::numeric_limits<std::size_t>::max());

}  // namespace earc
