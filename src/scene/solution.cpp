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

}  // namespace earc
