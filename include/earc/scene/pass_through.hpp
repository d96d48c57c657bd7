// Whether a scenario's resolution lets a robot pass through an obstacle
// unseen. A solution is checked at every step and at every step's
// midpoint (the contract, formats.md): a robot that can move further
// between two such instants than an obstacle's thinnest extent plus its
// own can be on one side of it at one instant and on the other at the
// next, and the solution is still valid. The contract asks for obstacles
// thicker than twice the largest step; this asks only whether crossing
// is possible at all, with the robots' own thickness counted.
#pragma once

#include <string>
#include <string_view>

#include "earc/scene/scenario.hpp"

namespace earc {

// An upper bound on how far any point of the robot's body moves in one step
// of the resolution.
double largestStepMotion(const RobotSpec& robot, const Resolution& resolution);

// The robot's thinnest extent: a disc's diameter, a box's shorter side, a
// link's diameter.
double thinnestExtent(const RobotSpec& robot);
double thinnestExtent(const Obstacle& obstacle);

// One line saying which robot can cross which obstacle between two
// checked instants (the one with the widest margin, and how many other
// obstacles are as thin for some robot), or "" when none can.
std::string passThroughWarning(const Scenario& scenario);

// The warning as a command prints it ("PROGRAM: warning: FILE: resolution:
// ...", printable, one line); "" when passThroughWarning says nothing.
std::string passThroughWarningLine(const Scenario& scenario, const std::string& scenario_file,
                                   std::string_view program);

}  // namespace earc
