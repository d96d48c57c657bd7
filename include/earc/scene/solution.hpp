// The solution model: the in-memory form of an earc.solution.v1 document.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "earc/scene/path.hpp"

namespace earc {

struct Solution {
  std::string scenario;  // the scenario's name
  std::string method;
  bool solved = false;
  std::vector<Path> paths;  // one per robot, in the scenario's order
  nlohmann::json stats = nlohmann::json::object();

  // Makespan: longest path in steps (max over robots of states - 1).
  std::size_t makespan() const;
  // Sum over robots of states - 1.
  std::size_t sumOfCosts() const;
};

}  // namespace earc
