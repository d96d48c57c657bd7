#include "earc/gen/generators.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "earc/collision/collision_world.hpp"
#include "earc/gen/placement.hpp"
#include "earc/gen/random.hpp"
#include "earc/scene/robot_model.hpp"

namespace earc::gen {

namespace {

// Obstacle layouts tried before giving up: a layout is dropped when some
// robot finds no valid start and goal in one free component.
constexpr int kMaxLayouts = 50;
constexpr int kMinRobots = 2;
constexpr int kMaxRobots = 128;
// Obstacles are thicker than twice the largest step (0.05), so a motion
// checked at steps and midpoints cannot jump through one.
constexpr double kMinObstacleSide = 0.2;

// Shortest readable form of a number ("20", "20.5").
std::string compact(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

void requireRange(const char* what, double v, double lo, double hi) {
  if (!(v >= lo && v <= hi))
    throw SettingError(what, "must be in [" + compact(lo) + ", " + compact(hi) + "], got " + compact(v));
}

// "m7": built by appending, as "m" + std::to_string(i) trips GCC 12's
// false -Wrestrict warning.
std::string indexedName(char prefix, int i) {
  std::string name(1, prefix);
  name += std::to_string(i);
  return name;
}

int armPairs(int robots) { return (robots + 1) / 2; }

// A random box with sides in [min_side, max_side] and its centre drawn so
// the whole box lies in `area`; angle 0 unless rotated.
Obstacle randomBox(Random& rng, const geo::Aabb& area, double min_side, double max_side, bool rotated) {
  Obstacle o;
  o.type = Obstacle::Type::Box;
  o.size = {roundCoordinate(rng.uniform(min_side, max_side)), roundCoordinate(rng.uniform(min_side, max_side))};
  o.angle = rotated ? roundCoordinate(rng.uniform(0.0, std::numbers::pi)) : 0.0;
  const double c = std::abs(std::cos(o.angle)), s = std::abs(std::sin(o.angle));
  // Half extents plus 1e-4, so that rounding the centre keeps the box inside.
  const double hx = 0.5 * (o.size.x * c + o.size.y * s) + 1e-4, hy = 0.5 * (o.size.x * s + o.size.y * c) + 1e-4;
  o.center = {roundCoordinate(rng.uniform(area.lo.x + hx, std::max(area.lo.x + hx, area.hi.x - hx))),
              roundCoordinate(rng.uniform(area.lo.y + hy, std::max(area.lo.y + hy, area.hi.y - hy)))};
  return o;
}

std::string mobileName(const MobileSettings& s) {
  std::string n = "mobile" + footprintTag(s.footprint);
  if (s.workspace != MobileSettings{}.workspace) n += "-w" + compact(s.workspace);
  if (s.obstacles > 0) {
    n += "-obst";
    if (s.obstacles != kDefaultMobileObstacles) n += std::to_string(s.obstacles);
    if (s.rotated_obstacles) n += "-rot";
  }
  return n + "-" + std::to_string(s.robots) + "-s" + std::to_string(s.seed);
}

std::string armsName(const ArmSettings& s) {
  std::string n = "arms";
  if (s.obstacles > 0) {
    n += "-obst";
    if (s.obstacles != defaultArmObstacles(s.robots)) n += std::to_string(s.obstacles);
    if (s.rotated_obstacles) n += "-rot";
  }
  return n + "-" + std::to_string(s.robots) + "-s" + std::to_string(s.seed);
}

}  // namespace

std::string footprintTag(const MobileFootprint& f) {
  if (f.shape != MobileShape::Disc) return "";
  return f.radius == MobileFootprint{}.radius ? "-disc" : "-disc-r" + compact(f.radius);
}

RobotSpec mobileRobot(int index, const MobileFootprint& f) {
  RobotSpec r;
  r.name = indexedName('m', index);
  r.kind = RobotKind::Mobile;
  r.shape = f.shape;
  if (f.shape == MobileShape::Disc)
    r.radius = f.radius;
  else
    r.box_size = f.box_size;
  return r;
}

void requireFootprint(const MobileFootprint& f, double workspace_side, const std::string& space) {
  const double max_radius = 0.25 * workspace_side, max_box_side = 0.5 * workspace_side;
  if (f.shape == MobileShape::Disc) {
    requireRange("radius", f.radius, 0.01, max_radius);
    return;
  }
  // The box is no option of earc-scenario (it is always 0.6 x 0.4): one too
  // big is a space too small, and the way out is the other shape.
  if (!(std::max(f.box_size.x, f.box_size.y) <= max_box_side))
    throw SettingError("shape", space + " is too small for the " + compact(f.box_size.x) + " x " + compact(f.box_size.y) +
                                    " box footprint (a box's sides must be at most half the smaller side, " +
                                    compact(max_box_side) + "): use --shape disc with --radius at most " +
                                    compact(max_radius));
  requireRange("box length", f.box_size.x, 0.01, max_box_side);
  requireRange("box width", f.box_size.y, 0.01, max_box_side);
}

Scenario generateMobile(const MobileSettings& settings) {
  requireRange("robots", settings.robots, kMinRobots, kMaxRobots);
  requireRange("obstacles", settings.obstacles, 0, 1000);
  requireRange("workspace", settings.workspace, 2.0, 1000.0);
  // Sides of obstacles that are not drawn cannot be wrong; with obstacles,
  // the largest must fit, said of the workspace, which a user sets.
  if (settings.obstacles > 0) {
    requireRange("obstacle_min_side", settings.obstacle_min_side, kMinObstacleSide, settings.obstacle_max_side);
    requireRange("workspace", settings.workspace, std::max(2.0, settings.obstacle_max_side), 1000.0);
  }
  const MobileFootprint& f = settings.footprint;
  requireFootprint(f, settings.workspace, "the " + compact(settings.workspace) + " x " + compact(settings.workspace) + " workspace");

  Random rng(settings.seed);
  Scenario s;
  s.name = mobileName(settings);
  s.workspace = {{0.0, 0.0}, {settings.workspace, settings.workspace}};
  for (int layout = 0; layout < kMaxLayouts; ++layout) {
    s.obstacles.clear();
    for (int k = 0; k < settings.obstacles; ++k)
      s.obstacles.push_back(randomBox(rng, s.workspace, settings.obstacle_min_side, settings.obstacle_max_side,
                                      settings.rotated_obstacles));
    s.robots.clear();
    for (int i = 0; i < settings.robots; ++i) s.robots.push_back(mobileRobot(i, f));
    const CollisionWorld world(s);
    auto disc_free = [&world](geo::Vec2 c, double r) { return world.bodyFree(geo::Body::disc(c, r)); };
    if (placeMobileRobots(s, world, disc_free, rng)) return s;
  }
  throw CrowdedError("could not place " + std::to_string(settings.robots) + " robots in " +
                           std::to_string(kMaxLayouts) + " obstacle layouts: use fewer robots or obstacles");
}

int defaultArmObstacles(int robots) { return armPairs(robots); }

Scenario generateArms(const ArmSettings& settings) {
  requireRange("robots", settings.robots, kMinRobots, kMaxRobots);
  requireRange("obstacles", settings.obstacles, 0, 1000);
  requireRange("obstacle_min_side", settings.obstacle_min_side, kMinObstacleSide, settings.obstacle_max_side);
  // Any box, however turned, must fit in the band between the rows.
  requireRange("obstacle_max_side", settings.obstacle_max_side, settings.obstacle_min_side,
               (kArmFacingDistance - 2.0 * kArmBaseClearance) / std::numbers::sqrt2);

  const int pairs = armPairs(settings.robots);
  const double lower_y = kArmWorkspaceMargin, upper_y = kArmWorkspaceMargin + kArmFacingDistance;
  Scenario s;
  s.name = armsName(settings);
  s.workspace = {{0.0, 0.0},
                 {2.0 * kArmWorkspaceMargin + kArmPairSpacing * (pairs - 1), upper_y + kArmWorkspaceMargin}};
  std::vector<RobotSpec> arms;
  for (int i = 0; i < settings.robots; ++i) {
    RobotSpec r;
    r.name = indexedName('a', i);
    r.kind = RobotKind::Manipulator;
    const bool upper = i % 2 == 1;
    r.base_position = {kArmWorkspaceMargin + kArmPairSpacing * (i / 2), upper ? upper_y : lower_y};
    r.base_angle = upper ? -std::numbers::pi / 2 : std::numbers::pi / 2;
    r.links.assign(kArmLinks, kArmLinkLength);
    r.link_radius = kArmLinkRadius;
    r.joint_limits.assign(kArmLinks, {-kArmJointLimit, kArmJointLimit});
    r.joint_limits[0] = {-kArmJoint1Limit, kArmJoint1Limit};
    arms.push_back(std::move(r));
  }

  // Obstacles lie between the rows, kArmBaseClearance above the lower
  // bases and below the upper ones, and horizontally within reach.
  const geo::Aabb band{{kArmWorkspaceMargin - 0.5 * kArmPairSpacing, lower_y + kArmBaseClearance},
                       {s.workspace.hi.x - kArmWorkspaceMargin + 0.5 * kArmPairSpacing, upper_y - kArmBaseClearance}};
  Random rng(settings.seed);
  for (int layout = 0; layout < kMaxLayouts; ++layout) {
    s.obstacles.clear();
    for (int k = 0; k < settings.obstacles; ++k)
      s.obstacles.push_back(
          randomBox(rng, band, settings.obstacle_min_side, settings.obstacle_max_side, settings.rotated_obstacles));
    s.robots = arms;
    const CollisionWorld world(s);
    if (placeStartsAndGoals(s, world, rng, {})) return s;
  }
  throw CrowdedError("could not place " + std::to_string(settings.robots) + " arms in " +
                           std::to_string(kMaxLayouts) + " obstacle layouts: use fewer obstacles");
}

}  // namespace earc::gen
