// libFuzzer target: the solution parser (earc.solution.v1 text ->
// Solution), both free-standing and against a fixed scenario (robot names
// and dimensions checked), then written back. Bad input must end in
// InputError; anything else escaping is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"

namespace {

// The fixtures' two discs (m0, m1, as in tests/data/solutions/swap-discs__*)
// and a three-joint arm: paths of two dimensions for the checks to tell apart.
const char* kScenario = R"({
  "format": "earc.scenario.v1", "name": "swap-discs",
  "workspace": {"min": [0, 0], "max": [10, 10]},
  "obstacles": [],
  "robots": [
    {"name": "m0", "type": "mobile", "shape": {"type": "disc", "radius": 0.3},
     "start": [2, 5, 0], "goal": [3, 5, 0]},
    {"name": "m1", "type": "mobile", "shape": {"type": "disc", "radius": 0.3},
     "start": [3, 5, 0], "goal": [2, 5, 0]},
    {"name": "a0", "type": "manipulator", "base": [5, 5, 0], "links": [1, 1, 1],
     "link_radius": 0.1, "joint_limits": [[-3, 3], [-2.8, 2.8], [-2.8, 2.8]],
     "start": [0, 0, 0], "goal": [0, 1.5, 1.5]}
  ],
  "resolution": {"translation": 1.0, "rotation": 0.5, "joint": 0.1}
})";

const earc::Scenario& scenario() {
  static const earc::Scenario s = earc::scenarioFromJson(earc::parseJsonText(kScenario, "fixed"), "fixed");
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  nlohmann::json doc;
  try {
    doc = earc::parseJsonText(text, "fuzz.json");
  } catch (const earc::InputError&) {
    return 0;
  }
  for (const earc::Scenario* against : {static_cast<const earc::Scenario*>(nullptr), &scenario()}) {
    try {
      earc::InputWarnings warnings;  // made, not printed
      earc::Solution s = earc::solutionFromJson(doc, against, "fuzz.json", &warnings);
      (void)s.makespan();
      (void)s.sumOfCosts();
      if (against && s.robot_names.empty()) s.nameRobots(*against);
      if (s.robot_names.size() == s.paths.size()) (void)earc::solutionToJson(s).dump();
    } catch (const earc::InputError&) {
    }
  }
  return 0;
}
