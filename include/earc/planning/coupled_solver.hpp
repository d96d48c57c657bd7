// Planning in the composite configuration space of a few robots (OMPL
// RRT-Connect on a compound space restricted to a local region), returning
// a time-stamped local solution. Used by ARC's hierarchy, by the coupled
// whole-problem baseline and by the experience database builder.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/composite.hpp"
#include "earc/planning/subproblem.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

struct CoupledSettings {
  // The attempt's budget, within `within` (capped there: seconds of work
  // when that deadline's budgets count work, see Deadline::withWorkBudgets).
  double time_limit_s = 1.0;
  Deadline within;
  bool simplify = true;        // shortcut the composite path before time-stamping
  // After simplifying, polish the path (see polishComposite). For a few
  // robots (subproblems, repairs, stored experiences); the whole-problem
  // baseline keeps it off, as a motion of thousands of robots costs seconds.
  bool polish = false;
};

struct CoupledQuery {
  std::vector<const RobotModel*> robots;
  std::vector<std::vector<double>> starts;
  std::vector<std::vector<double>> goals;
  std::vector<ConfigBox> region;  // sampling bounds per robot (empty: whole space)
};

// Valid paths of one length from the starts to the goals (every step and
// midpoint), or nullopt when none is found within the time limit.
// Deterministic for a seed unless the time limit stops it.
std::optional<LocalSolution> solveCoupled(const CollisionWorld& world, const CoupledQuery& query,
                                          const CoupledSettings& settings, std::uint64_t seed);

// Time-stamps a composite waypoint sequence: each segment is split into the
// largest number of steps any robot needs for it, so all robots move and
// arrive together. waypoints[w][r] is robot r's configuration at waypoint w.
LocalSolution timeStampComposite(const std::vector<const RobotModel*>& robots,
                                 const std::vector<std::vector<std::vector<double>>>& waypoints);

// Makes a valid composite waypoint sequence shorter in steps, keeping it
// valid and its ends (mobile robots turned steadily, shortcut, time-stamped,
// shortcut again). Stops early at the deadline.
void polishComposite(const CompositeChecker& checker, std::vector<CompositeState>& waypoints, std::mt19937_64& rng,
                     const Deadline& deadline);

// Maximal runs [first, last] of steps whose motion t -> t+1 is invalid; past
// the checker's deadline everything reads invalid: ask checker.outOfTime().
using StepRun = std::pair<std::size_t, std::size_t>;
std::vector<StepRun> invalidRuns(const CompositeChecker& checker, const std::vector<Path>& paths);

// Time-stamped paths with each invalid run replanned in the composite space
// between the valid states around it; without paths (and `why`) when one failed.
struct RunRepair {
  std::optional<std::vector<Path>> paths;
  bool out_of_time = false;  // no time was left for a run (rather than its replanning failing)
  std::string why;           // "no time left to repair" or "repair failed"
};
RunRepair repairRuns(const CollisionWorld& world, const std::vector<const RobotModel*>& robots,
                     const std::vector<Path>& paths, const std::vector<StepRun>& runs,
                     const std::vector<ConfigBox>& region, double time_per_run_s, const Deadline& deadline,
                     std::uint64_t seed);

}  // namespace earc
