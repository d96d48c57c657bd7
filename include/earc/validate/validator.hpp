// The contract's validity rules for a solution (shared/spec/formats.md,
// "What makes a solution valid"), implemented independently of any planner.
#pragma once

#include <string>
#include <vector>

#include "earc/scene/scenario.hpp"
#include "earc/scene/solution.hpp"

namespace earc {

struct Violation {
  enum class Type { NotSolved, Paths, Start, Goal, Resolution, JointLimit, Workspace, Obstacle, SelfCollision, RobotRobot };
  Type type = Type::Paths;
  double t = -1;             // time step; x.5 for the midpoint of x and x+1; -1 when none
  std::vector<int> robots;   // scenario indices
  std::string detail;        // one readable line
};

const char* violationTypeName(Violation::Type t);

struct ValidationReport {
  bool valid = false;
  std::size_t violation_count = 0;      // all found (one per type, instant and robot/pair)
  std::vector<Violation> violations;    // the first ones, earliest first
  std::size_t makespan = 0;
  std::size_t sum_of_costs = 0;
  double total_distance = 0.0;
};

struct ValidatorSettings {
  std::size_t max_listed = 20;  // violations kept in the report
};

ValidationReport validateSolution(const Scenario& scenario, const Solution& solution,
                                  const ValidatorSettings& settings = {});

}  // namespace earc
