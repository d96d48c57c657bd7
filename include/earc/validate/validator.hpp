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

// Checks a solution against the contract; violations ordered as
// check_solution.py lists them (structure and endpoints, then by instant,
// kind and robot). Instants are checked on all cores.
ValidationReport validateSolution(const Scenario& scenario, const Solution& solution,
                                  const ValidatorSettings& settings = {});

// The contract's per-instant rules (workspace, obstacles, self-collision,
// robot-robot contact, joint limits, with 1e-6 slack) for robots placed at
// one configuration each. Thread-safe.
class InstantChecker {
 public:
  explicit InstantChecker(const Scenario& scenario);
  ~InstantChecker();
  InstantChecker(const InstantChecker&) = delete;
  InstantChecker& operator=(const InstantChecker&) = delete;

  // robots[i] (scenario indices, ascending) at q[i]: appends, with time t,
  // each robot's Workspace, Obstacle and SelfCollision violations (none where
  // clean[i] says q[i] is known free of them), then RobotRobot per touching pair.
  void checkGeometry(std::span<const int> robots, std::span<const double* const> q, double t,
                     std::vector<Violation>& out, std::span<const char> clean = {}) const;
  // Appends one JointLimit violation per joint of an arm outside its limits.
  void checkJointLimits(int robot, const double* q, double t, std::vector<Violation>& out) const;

  const Scenario& scenario() const { return scenario_; }

 private:
  struct Impl;
  const Scenario& scenario_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace earc
