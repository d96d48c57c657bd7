// The text of a generated scenario file: the contract's JSON with one
// obstacle and one robot per line, so a dataset reads and diffs line by
// line (nlohmann's indented dump puts every number on its own line).
#pragma once

#include <string>

#include "earc/scene/scenario.hpp"

namespace earc::gen {

std::string scenarioText(const Scenario& s);

// scenarioText written atomically (writeTextFileAtomic).
void writeScenarioFile(const std::string& path, const Scenario& s);

// One line for the user: "NAME, N robots, K obstacles".
std::string scenarioSummary(const Scenario& s);

}  // namespace earc::gen
