// The solution model: the in-memory form of an earc.solution.v1 document.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "earc/scene/path.hpp"

namespace earc {

struct Scenario;

struct Solution {
  std::string scenario;  // the scenario's name
  std::string method;
  bool solved = false;
  std::vector<Path> paths;  // one per robot, in the scenario's order
  nlohmann::json stats = nlohmann::json::object();
  // The robot of paths[i], as the file names it (empty: the scenario's
  // order). Kept as read, so that the validator can report a path out of
  // order or for an unknown robot; solutionToJson needs them (nameRobots()).
  std::vector<std::string> robot_names;

  // Sets robot_names to the scenario's robot names (paths in scenario order).
  void nameRobots(const Scenario& scenario);

  // Makespan: longest path in steps (max over robots of states - 1; an
  // empty path counts 0).
  std::size_t makespan() const;
  // Sum over robots of states - 1.
  std::size_t sumOfCosts() const;
  // Whether any path holds a state.
  bool hasPaths() const;
};

// Why a plan was not solved, from its stats' "failure" (the planner's list
// of causes, or one string): the causes joined by commas ("time_limit"),
// "" when there is none.
std::string failureReasons(const nlohmann::json& stats);

}  // namespace earc
