// Reading back RobotModel::geometrySignature(): stored experiences name
// their robots by signature, and a row from a file must name robots that
// exist. Kept out of robot_model.hpp, which nearly everything includes.
#pragma once

#include <optional>
#include <string_view>

#include "earc/scene/scenario.hpp"

namespace earc {

// The robot (kind, footprint or links, link radius and joint limits; no
// name, placement, start or goal) whose geometrySignature() is exactly
// `signature`, or nothing when no valid robot has that signature. The
// writer stays the one description of the format: what is read is
// written again and must come out the same.
std::optional<RobotSpec> robotFromSignature(std::string_view signature);

}  // namespace earc
