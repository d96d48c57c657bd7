// The contract's validity rules for a solution (shared/spec/formats.md,
// "What makes a solution valid"), implemented independently of any planner.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "earc/scene/scenario.hpp"
#include "earc/scene/solution.hpp"

namespace earc {

struct Violation {
  // ScenarioName: the solution names another scenario than the one given.
  enum class Type { NotSolved, Paths, Start, Goal, Resolution, JointLimit, Workspace, Obstacle, SelfCollision, RobotRobot, ScenarioName };
  Type type = Type::Paths;
  double t = -1;             // time step; x.5 for the midpoint of x and x+1; -1 when none
                             // (Resolution: the step's first instant, as the checker reports it)
  std::vector<int> robots;   // scenario indices
  std::string detail;        // one readable line
  int obstacle = -1;         // Obstacle: the obstacle's index
  int joint = -1;            // JointLimit, and Resolution of an arm: the joint's index (0-based)
  double amount = 0.0;       // overlap, excess or change that broke the rule
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

// Violations are ordered as check_solution.py lists them: the problems found
// in the solution's structure (not solved, scenario name, paths) and its
// endpoints first, then everything else by instant, and at one instant
// by kind (resolution, joint limits, workspace, obstacle, self-collision,
// robot-robot), then by robot. Instants are checked on all cores.
ValidationReport validateSolution(const Scenario& scenario, const Solution& solution,
                                  const ValidatorSettings& settings = {});

// The contract's per-instant rules for robots placed at one configuration
// each: inside the workspace, clear of obstacles, no self-collision, no two
// robots touching (all with the contract's 1e-6 slack), and joint limits.
// Used for every instant of a solution and for a scenario's starts and goals.
// Thread-safe.
class InstantChecker {
 public:
  explicit InstantChecker(const Scenario& scenario);
  ~InstantChecker();
  InstantChecker(const InstantChecker&) = delete;
  InstantChecker& operator=(const InstantChecker&) = delete;

  // robots[i] (scenario indices, ascending) is at configuration q[i].
  // Appends, with time t: per robot one Workspace, one Obstacle per touched
  // obstacle and one SelfCollision violation; then one RobotRobot per
  // touching pair (robots ascending).
  void checkGeometry(std::span<const int> robots, std::span<const double* const> q, double t,
                     std::vector<Violation>& out) const;
  // Appends one JointLimit violation per joint of an arm outside its limits.
  void checkJointLimits(int robot, const double* q, double t, std::vector<Violation>& out) const;

  const Scenario& scenario() const { return scenario_; }

 private:
  struct Impl;
  const Scenario& scenario_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace earc
