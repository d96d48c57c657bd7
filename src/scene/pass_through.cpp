#include "earc/scene/pass_through.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "earc/util/format.hpp"

namespace earc {

namespace {

// A point at distance `radius` from a centre it turns about by `angle`
// moves by the chord, at most `radius * angle` and at most the diameter.
double turnMotion(double radius, double angle) { return std::min(radius * std::fabs(angle), 2.0 * radius); }

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

// How far any point of the robot's body can move in one step of the
// scenario's resolution (an upper bound: every joint or the heading
// turning by its full resolution at once, and the reference point moving
// by its full translation).
double largestStepMotion(const RobotSpec& robot, const Resolution& resolution) {
  if (robot.kind == RobotKind::Mobile) {
    if (robot.shape == MobileShape::Disc) return resolution.translation;  // turning moves no point of a disc
    const double half_diagonal = 0.5 * std::hypot(robot.box_size.x, robot.box_size.y);
    return resolution.translation + turnMotion(half_diagonal, resolution.rotation);
  }
  // Joint i turns everything beyond it, whose farthest point is the rest
  // of the chain's length plus the link radius away.
  double motion = 0.0, beyond = robot.link_radius;
  for (auto it = robot.links.rbegin(); it != robot.links.rend(); ++it) {
    beyond += *it;
    motion += turnMotion(beyond, resolution.joint);
  }
  return motion;
}

double thinnestExtent(const RobotSpec& robot) {
  if (robot.kind == RobotKind::Manipulator) return 2.0 * robot.link_radius;
  if (robot.shape == MobileShape::Disc) return 2.0 * robot.radius;
  return std::min(robot.box_size.x, robot.box_size.y);
}

double thinnestExtent(const Obstacle& obstacle) {
  if (obstacle.type == Obstacle::Type::Circle) return 2.0 * obstacle.radius;
  return std::min(obstacle.size.x, obstacle.size.y);
}

std::string passThroughWarning(const Scenario& scenario) {
  // Between two checked instants (half a step apart) a robot moves at
  // most half its step; to be clear of an obstacle on both sides it must
  // move by the obstacle's extent plus its own.
  struct Worst {
    std::size_t robot = 0, obstacle = 0;
    double reach = 0, margin = 0;
  };
  bool found = false;
  Worst worst;
  std::size_t crossable = 0;
  for (std::size_t o = 0; o < scenario.obstacles.size(); ++o) {
    bool counted = false;
    for (std::size_t r = 0; r < scenario.robots.size(); ++r) {
      const double reach = 0.5 * largestStepMotion(scenario.robots[r], scenario.resolution);
      const double margin = reach - thinnestExtent(scenario.obstacles[o]) - thinnestExtent(scenario.robots[r]);
      if (!(margin > 0)) continue;
      if (!counted) ++crossable;
      counted = true;
      if (!found || margin > worst.margin) worst = {r, o, reach, margin};
      found = true;
    }
  }
  if (!found) return "";
  const RobotSpec& robot = scenario.robots[worst.robot];
  const char* field = robot.kind == RobotKind::Manipulator ? "joint"
                      : robot.shape == MobileShape::Disc  ? "translation"
                                                          : "translation, rotation";
  std::string line = "resolution: robot '" + robot.name + "' can move " + number(worst.reach) +
                     " between two checked instants (half a step of resolution." + field + "), more than obstacle " +
                     std::to_string(worst.obstacle) + "'s thickness (" +
                     number(thinnestExtent(scenario.obstacles[worst.obstacle])) + ") and its own (" +
                     number(thinnestExtent(robot)) + ") together: a valid solution may pass through the obstacle";
  if (crossable > 1) line += " (and through " + std::to_string(crossable - 1) + " other obstacles)";
  return line + "; a finer resolution prevents this";
}

// The warning as a command prints it on stderr for the scenario read from
// `scenario_file`: "PROGRAM: warning: FILE: resolution: ...", the file
// name and the warning made printable (printableText, 4096 bytes at most),
// without a line break; "" when passThroughWarning says nothing.
std::string passThroughWarningLine(const Scenario& scenario, const std::string& scenario_file,
                                   std::string_view program) {
  const std::string warning = passThroughWarning(scenario);
  if (warning.empty()) return "";
  return std::string(program) + ": warning: " + printableText(scenario_file + ": " + warning, 4096);
}

}  // namespace earc
