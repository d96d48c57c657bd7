// Placing robots at random valid starts and goals: the part every scenario
// generator shares (mobile, arms, MovingAI maps).
#pragma once

#include <functional>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/random.hpp"
#include "earc/geometry/shapes.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/scene/scenario.hpp"

namespace earc::gen {

// Gap kept between any two bodies of a generated start or goal (robot,
// obstacle, border): a query that starts in contact is degenerate.
inline constexpr double kClearance = 0.1;

// Grid cell of the free-space connectivity test: 1/5 puts cell centres on
// the centre line of every unit grid cell (MovingAI maps).
inline constexpr double kFreeSpaceCell = 0.2;

// Generated coordinates are rounded to 1e-4 before they are checked, so the
// JSON stays short and what is checked is exactly what is written.
double roundCoordinate(double v);

// True when a disc lies inside the workspace and touches no obstacle.
using DiscFree = std::function<bool(geo::Vec2 centre, double radius)>;

// The free space of a disc robot cut into 4-connected components on a coarse
// grid; conservative: it never joins two separated regions.
class FreeSpaceGrid {
 public:
  FreeSpaceGrid(const geo::Aabb& workspace, double cell, double radius, DiscFree free);

  // The component of point p, or -1 when the disc at p cannot reach the
  // centre of its cell in a straight line (or that cell is not free).
  int componentOf(geo::Vec2 p) const;
  int componentCount() const { return components_; }

 private:
  geo::Aabb workspace_;
  double cell_;
  double radius_;
  DiscFree free_;
  int cols_ = 0;
  int rows_ = 0;
  int components_ = 0;
  std::vector<int> label_;  // per cell, row-major from the bottom left; -1 blocked
};

// The free-space region a configuration belongs to (-1: none usable). A
// robot's start and goal are drawn in the same region.
using RegionOf = std::function<int(const RobotModel& robot, const double* q)>;

// True when q is within the joint limits, free of self-collision, and every
// body part keeps kClearance from the obstacles and the workspace border.
bool clearOfWorld(const CollisionWorld& world, const RobotModel& robot, const double* q);

// Draws every robot's start and goal by rejection (clear of the world and of
// earlier robots, start and goal in one `region`). Returns false when a robot
// found no place within the attempt budget.
bool placeStartsAndGoals(Scenario& s, const CollisionWorld& world, Random& rng, const RegionOf& region);

// placeStartsAndGoals for mobile robots, start and goal in one component of
// the free space of the largest bounding disc; `free` tests a disc.
bool placeMobileRobots(Scenario& s, const CollisionWorld& world, const DiscFree& free, Random& rng);

// `base` with every robot's start and goal drawn again, a function of
// (base, seed). Throws CrowdedError when no placement is found.
Scenario redrawStartsAndGoals(const Scenario& base, std::uint64_t seed);

}  // namespace earc::gen
