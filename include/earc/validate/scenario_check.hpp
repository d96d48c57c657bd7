// Checks of a scenario that has been read, before anything plans with it.
#pragma once

#include <string>

#include "earc/io/json_io.hpp"
#include "earc/scene/scenario.hpp"

namespace earc {

// Throws InputError naming `file` and the field for the first geometric
// problem of a parsed scenario: a start or goal outside the workspace, in
// collision, beyond joint limits or touching another's; an arm's base outside.
void checkScenarioGeometry(const Scenario& s, const std::string& file);

// readScenarioFile, then checkScenarioGeometry; warnings as readScenarioFile
// gives them, only for a scenario accepted. Throws InputError.
Scenario loadScenario(const std::string& path, InputWarnings* warnings = nullptr);

}  // namespace earc
