#include "earc/gen/scenario_text.hpp"

#include <nlohmann/json.hpp>

#include "earc/io/json_io.hpp"

namespace earc::gen {

std::string scenarioText(const Scenario& s) {
  const nlohmann::json doc = scenarioToJson(s);
  std::string text = "{";
  bool first = true;
  for (const auto& [key, value] : doc.items()) {
    text += first ? "\n  " : ",\n  ";
    first = false;
    text += nlohmann::json(key).dump();
    text += ": ";
    // Lists of objects (obstacles, robots): one element per line.
    if (value.is_array() && !value.empty() && value.front().is_object()) {
      text += "[";
      for (std::size_t i = 0; i < value.size(); ++i) {
        text += i == 0 ? "\n    " : ",\n    ";
        text += value[i].dump();
      }
      text += "\n  ]";
    } else {
      text += value.dump();
    }
  }
  text += "\n}\n";
  return text;
}

void writeScenarioFile(const std::string& path, const Scenario& s) { writeTextFileAtomic(path, scenarioText(s)); }

std::string scenarioSummary(const Scenario& s) {
  std::string line = s.name;
  line += ", " + std::to_string(s.robots.size()) + " robots, ";
  line += std::to_string(s.obstacles.size()) + " obstacles";
  return line;
}

}  // namespace earc::gen
