// The data embedded in the viewer page, and the checks that a solution and
// its scenario belong together.
#include <algorithm>
#include <cmath>

#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"
#include "earc/view/viewer.hpp"

namespace earc::view {

using nlohmann::json;

// Checks that a solution belongs to the scenario: the same scenario name
// (when the solution names one) and, unless it has no paths at all (an
// unsolved solution), one non-empty path per robot in the scenario's order
// with the robot's dimension. Throws InputError naming `file`.
void checkSolutionMatches(const Scenario& sc, const Solution& sol, const std::string& file) {
  if (!sol.scenario.empty() && sol.scenario != sc.name)
    throw InputError(file, "$.scenario",
                     "the solution is for scenario \"" + sol.scenario + "\", not \"" + sc.name + "\"");
  if (sol.paths.empty()) {
    if (sol.solved && !sc.robots.empty()) throw InputError(file, "$.paths", "solved, but has no paths");
    return;  // unsolved: the page shows the scenario with a banner
  }
  if (sol.paths.size() != sc.robots.size())
    throw InputError(file, "$.paths",
                     "has " + std::to_string(sol.paths.size()) + " paths, the scenario has " +
                         std::to_string(sc.robots.size()) + " robots");
  for (std::size_t i = 0; i < sc.robots.size(); ++i) {
    const std::string where = "$.paths[" + std::to_string(i) + "]";
    const std::string& name = i < sol.robot_names.size() ? sol.robot_names[i] : sc.robots[i].name;
    if (name != sc.robots[i].name)
      throw InputError(file, where + ".robot",
                       "path of \"" + name + "\" where the scenario's robot " + std::to_string(i) + " is \"" +
                           sc.robots[i].name + "\" (paths must follow the scenario's order)");
    if (sol.paths[i].empty()) throw InputError(file, where + ".states", "empty path");
    if (sol.paths[i].dim() != sc.robots[i].dim())
      throw InputError(file, where + ".states",
                       "states of " + std::to_string(sol.paths[i].dim()) + " numbers, robot \"" + name + "\" has " +
                           std::to_string(sc.robots[i].dim()));
  }
}

json encodePath(const Path& path) {
  const auto d = static_cast<std::size_t>(path.dim());
  const std::vector<double>& raw = path.raw();
  std::vector<long long> out(raw.size());
  for (std::size_t k = 0; k < raw.size(); ++k) {
    const long long q = std::llround(raw[k] / kStateQuantum);
    out[k] = k < d ? q : q - std::llround(raw[k - d] / kStateQuantum);
  }
  return out;
}

json viewerData(const Scenario& sc, const Solution& sol, const json& trace) {
  std::size_t makespan = 0;
  json paths = json::array();
  for (const Path& p : sol.paths) {
    makespan = std::max(makespan, p.size() - 1);
    paths.push_back(encodePath(p));
  }
  json solution = {{"solved", sol.solved},
                   {"method", sol.method},
                   {"makespan", makespan},
                   {"quantum", kStateQuantum},
                   {"stats", sol.stats},
                   {"paths", std::move(paths)}};
  json scenario = scenarioToJson(sc);
  scenario.erase("format");
  scenario.erase("resolution");
  return {{"format", "earc.viewer.v1"}, {"scenario", std::move(scenario)}, {"solution", std::move(solution)},
          {"trace", trace}};
}

}  // namespace earc::view
