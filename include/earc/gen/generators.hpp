// Random scenario families of the E-ARC experiments (paper, "Experiments"):
// mobile robots in an open or cluttered square, and facing pairs of planar
// 5-DOF arms. Each generator is a pure function of its settings: the same
// seed gives the same scenario on every platform (see random.hpp), and
// every scenario it returns passes checkScenarioGeometry (validate/scenario_check.hpp).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "earc/geometry/shapes.hpp"
#include "earc/scene/scenario.hpp"

namespace earc::gen {

// A setting out of its range. setting() names the field ("robots",
// "workspace", "radius"); what() reads "workspace must be in [2, 1000],
// got 1", reason() the same without the field's name.
class SettingError : public std::invalid_argument {
 public:
  SettingError(const std::string& setting, const std::string& reason)
      : std::invalid_argument(setting + " " + reason), setting_(setting), reason_(reason) {}
  const std::string& setting() const { return setting_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string setting_, reason_;
};

// No layout was found: the request is too crowded (too many robots or
// obstacles for the space). what() says so and what to change.
class CrowdedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The body of a generated mobile robot.
struct MobileFootprint {
  MobileShape shape = MobileShape::Box;
  geo::Vec2 box_size{0.6, 0.4};  // full length along the heading, full width
  double radius = 0.3;           // disc
};

// The footprint's part of a scenario's name: "" for the box, "-disc" for
// a disc of the default radius, "-disc-r0.8" for another, so that
// scenarios of different robots are not named alike.
std::string footprintTag(const MobileFootprint& f);

// Robot "m<index>" with this footprint; start and goal left empty.
RobotSpec mobileRobot(int index, const MobileFootprint& footprint);

// Throws SettingError unless the footprint's sizes are 0.01 to a quarter
// (disc radius) or half (box sides) of `workspace_side`; a box too big is
// an error of "shape" whose reason begins with `space` ("the 1 x 1 map").
void requireFootprint(const MobileFootprint& footprint, double workspace_side, const std::string& space);

// Obstacle count used when obstacles are asked for without a count.
inline constexpr int kDefaultMobileObstacles = 12;

struct MobileSettings {
  int robots = 16;               // 2..128
  int obstacles = 0;             // random boxes
  bool rotated_obstacles = false;
  double workspace = 20.0;       // side of the square [0, w] x [0, w]
  double obstacle_min_side = 1.0;
  double obstacle_max_side = 3.0;
  MobileFootprint footprint;
  std::uint64_t seed = 1;
};

// Throws SettingError for settings out of range and CrowdedError when no
// valid layout was found. The obstacles' sides are checked only when there
// are obstacles; then the workspace must be as large as the largest side.
Scenario generateMobile(const MobileSettings& settings);

// Arm layout: arm 2k is the lower arm of pair k, arm 2k+1 the upper one.
inline constexpr int kArmLinks = 5;
inline constexpr double kArmLinkLength = 0.5;
inline constexpr double kArmLinkRadius = 0.05;
inline constexpr double kArmJoint1Limit = 3.141592653589793;  // joint 1: [-pi, pi]
inline constexpr double kArmJointLimit = 2.6;                 // joints 2..5
inline constexpr double kArmFacingDistance = 4.0;  // lower to upper base of a pair
inline constexpr double kArmPairSpacing = 3.0;     // between neighbouring pairs
// Base to workspace border: full reach (5 x 0.5 + 0.05) plus 0.45.
inline constexpr double kArmWorkspaceMargin = 3.0;
// Obstacles between the rows keep this distance from every base.
inline constexpr double kArmBaseClearance = 0.6;

struct ArmSettings {
  int robots = 4;                // 2..128
  int obstacles = 0;             // random boxes between the two rows
  bool rotated_obstacles = false;
  double obstacle_min_side = 0.4;
  double obstacle_max_side = 1.0;
  std::uint64_t seed = 1;
};

// Default obstacle count for arms: one per pair.
int defaultArmObstacles(int robots);

// Throws SettingError and CrowdedError as generateMobile does.
Scenario generateArms(const ArmSettings& settings);

}  // namespace earc::gen
