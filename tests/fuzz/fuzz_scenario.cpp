// libFuzzer target: the scenario parser (earc.scenario.v1 text -> Scenario,
// then the geometric checks of starts and goals, as earc-plan and
// earc-scenario run them on a file). Bad input must end in InputError, the
// one-line exit-2 error of every CLI; anything else escaping is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/validate/scenario_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // Warnings (unknown keys, degrees) collected, not printed: they are
    // made and dropped for every input.
    earc::InputWarnings warnings;
    earc::Scenario s = earc::scenarioFromJson(earc::parseJsonText(text, "fuzz.json"), "fuzz.json", &warnings);
    earc::checkScenarioGeometry(s, "fuzz.json");
    (void)earc::scenarioToJson(s).dump();
  } catch (const earc::InputError&) {
  }
  return 0;
}
