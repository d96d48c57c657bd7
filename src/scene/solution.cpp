#include "earc/scene/solution.hpp"

#include <algorithm>

#include "earc/scene/scenario.hpp"

namespace earc {

void Solution::nameRobots(const Scenario& scenario) {
  robot_names.clear();
  for (const RobotSpec& r : scenario.robots) robot_names.push_back(r.name);
}

std::size_t Solution::makespan() const {
  std::size_t m = 0;
  for (const Path& p : paths)
    if (!p.empty()) m = std::max(m, p.size() - 1);
  return m;
}

std::size_t Solution::sumOfCosts() const {
  std::size_t sum = 0;
  for (const Path& p : paths)
    if (!p.empty()) sum += p.size() - 1;
  return sum;
}

bool Solution::hasPaths() const {
  return std::any_of(paths.begin(), paths.end(), [](const Path& p) { return !p.empty(); });
}

std::string failureReasons(const nlohmann::json& stats) {
  if (!stats.is_object() || !stats.contains("failure")) return "";
  const auto& f = stats["failure"];
  auto text = [](const nlohmann::json& x) { return x.is_string() ? x.get<std::string>() : x.dump(); };
  if (!f.is_array()) return text(f);
  std::string why;
  for (const auto& x : f) why += (why.empty() ? "" : ",") + text(x);
  return why;
}

}  // namespace earc
