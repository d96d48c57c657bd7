// Reading back RobotModel::geometrySignature(): stored experiences name
// their robots by signature, and a row from a file must name robots that
// exist. Kept out of robot_model.hpp, which nearly everything includes.
#pragma once

#include <optional>
#include <string_view>

#include "earc/scene/scenario.hpp"

namespace earc {

// The robot (geometry only: no name, placement, start or goal) whose
// geometrySignature() is exactly `signature`; nothing when no valid robot
// has it. Thread-safe.
std::optional<RobotSpec> robotFromSignature(std::string_view signature);

}  // namespace earc
