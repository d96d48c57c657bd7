// The scene-level checks of a scenario that has been read: where its robots
// start and end. Kept out of the JSON reader, which knows no geometry.
#include "earc/validate/scenario_check.hpp"

#include <cmath>
#include <numbers>

#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/util/format.hpp"
#include "earc/validate/validator.hpp"

namespace earc {

namespace {

// "$.robots" + 2 -> "$.robots[2]", the JSON path of an element.
std::string jsonIndex(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

// A joint beyond a full turn (and a little, for 2 pi rounded up) was
// written in degrees.
constexpr double kDegreesBeyond = 0.01;

}  // namespace

void checkScenarioGeometry(const Scenario& s, const std::string& file) {
  // An arm's base does not move: outside the workspace, every
  // configuration is, and "start is outside" would send the user to the
  // joint angles.
  for (std::size_t i = 0; i < s.robots.size(); ++i) {
    const RobotSpec& r = s.robots[i];
    if (r.kind != RobotKind::Manipulator) continue;
    const double out = geo::excessOutside(geo::Body::disc(r.base_position, r.link_radius), s.workspace);
    if (out > geo::kContactTolerance)
      throw InputError(file, jsonIndex("$.robots", i) + ".base",
                       "base is outside the workspace by " + formatNumber(out));
  }
  const InstantChecker checker(s);
  std::vector<int> all(s.robots.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  std::vector<Violation> found;
  for (const bool goal : {false, true}) {
    const char* label = goal ? "goal" : "start";
    std::vector<const double*> q;
    for (const RobotSpec& r : s.robots) q.push_back(goal ? r.goal.data() : r.start.data());
    for (int i : all) checker.checkJointLimits(i, q[static_cast<std::size_t>(i)], 0, found);
    checker.checkGeometry(all, q, 0, found);
    if (found.empty()) continue;
    // The first problem, named by the robot's path in the document. A
    // robot-robot contact is reported at the later robot.
    const Violation& v = found.front();
    const int robot = v.robots.back();
    std::string where = jsonIndex("$.robots", static_cast<std::size_t>(robot)) + "." + label;
    std::string reason;
    switch (v.type) {
      case Violation::Type::JointLimit: {
        const auto [lo, hi] = s.robots[static_cast<std::size_t>(robot)].joint_limits[static_cast<std::size_t>(v.joint)];
        where = jsonIndex(where, static_cast<std::size_t>(v.joint));
        reason = std::string(label) + " is outside the joint limits [" + formatNumber(lo) + ", " +
                 formatNumber(hi) + "]";
        // A joint of -30 or 90: degrees, most likely, as for headings.
        if (const double angle = q[static_cast<std::size_t>(robot)][v.joint];
            std::abs(angle) > 2 * std::numbers::pi + kDegreesBeyond)
          reason += " (" + formatNumber(angle) + " is more than a full turn: angles are in radians, and this looks "
                    "like degrees)";
        break;
      }
      case Violation::Type::Workspace:
        reason = std::string(label) + " is outside the workspace by " + formatNumber(v.amount);
        break;
      case Violation::Type::Obstacle:
        reason = std::string(label) + " is in collision with obstacle " + std::to_string(v.obstacle) + " (" +
                 jsonIndex("$.obstacles", static_cast<std::size_t>(v.obstacle)) + ", " +
                 (s.obstacles[static_cast<std::size_t>(v.obstacle)].type == Obstacle::Type::Box ? "box" : "circle") +
                 "), overlap " + formatNumber(v.amount);
        break;
      case Violation::Type::SelfCollision:
        reason = std::string(label) + " is in self-collision: " + v.detail;
        break;
      case Violation::Type::RobotRobot:
        reason = std::string(label) + " touches the " + label + " of robot \"" +
                 s.robots[static_cast<std::size_t>(v.robots.front())].name + "\" (" +
                 jsonIndex("$.robots", static_cast<std::size_t>(v.robots.front())) + "), overlap " +
                 formatNumber(v.amount);
        break;
      default: reason = std::string(label) + ": " + v.detail; break;
    }
    throw InputError(file, where, reason);
  }
}

Scenario loadScenario(const std::string& path, InputWarnings* warnings) {
  // Warnings only for a scenario that is read: refused, it gets one line.
  InputWarnings found;
  Scenario s = readScenarioFile(path, &found);
  checkScenarioGeometry(s, path);
  if (warnings == nullptr) printInputWarnings(found);
  else warnings->insert(warnings->end(), found.begin(), found.end());
  return s;
}

}  // namespace earc
