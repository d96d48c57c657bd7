// Adaptive Robot Coordination (ARC), the paper's Algorithm 1: plan every
// robot alone, then repeatedly cut the earliest conflict into a local
// subproblem, solve it with a hierarchy of solvers (growing the window when
// they fail, merging robots whose earlier local solutions would otherwise be
// undone), and splice the local solution into the plan.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <tuple>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/planning/conflict.hpp"
#include "earc/planning/planner.hpp"
#include "earc/planning/solver.hpp"

namespace earc {

// A local solution spliced into the plan: which robots, and over which
// global steps. Later conflicts of these robots inside that span pull the
// whole group into the new subproblem.
struct ResolvedSpan {
  std::vector<int> robots;
  std::size_t t0 = 0;
  std::size_t t1 = 0;
};

// The subproblem for a conflict among `robots` at expansion `level`: a window
// of initial_window * 2^level steps each side, regions growing with the
// level; the whole problem once the window covers every path at the last level.
Subproblem createSubproblem(const Conflict& conflict, const std::vector<int>& robots, int level,
                            const std::vector<const RobotModel*>& models, const std::vector<Path>& paths,
                            const CollisionWorld& world, const PlannerSettings& settings);

// Retimes each mobile robot of `local` (a solution of `sub`) along its own
// route inside the window, against the group and the robots outside it as
// `paths` has them; its length stays. Returns the steps of arrival saved.
std::int64_t retimeLocalSolution(const Subproblem& sub, LocalSolution& local,
                                 const std::vector<const RobotModel*>& models, const std::vector<Path>& paths,
                                 const CollisionWorld& world, const Deadline& deadline);

// What restampLocalSolution did: whether it re-stamped the answer (else it
// is left in lockstep), and then whether around the robots outside too.
struct RestampReport {
  bool restamped = false;
  bool around_outside = false;
  std::int64_t steps_saved = 0;  // summed over the robots' arrivals
};

// Time-stamps the composite answer `local` of mobile robots robot by robot,
// each along its route at full speed after those before it, none arriving
// later; leaves it in lockstep when some robot finds no timing.
RestampReport restampLocalSolution(const Subproblem& sub, LocalSolution& local,
                                   const std::vector<const RobotModel*>& models, const std::vector<Path>& paths,
                                   const CollisionWorld& world, const Deadline& deadline);

// UpdateSolution: replaces steps [t_start, t_end] of each subproblem robot's
// path by its local path; the rest of the path follows (shifted in time when
// the local path is longer than the span it replaces).
void splice(std::vector<Path>& paths, const Subproblem& sub, const LocalSolution& local);

// Adds to `robots` those of every span overlapping steps [t0, t1] that shares
// a robot with them (one hop), unless the group would pass max_robots.
// Returns how many were added.
int mergeOverlapping(std::vector<int>& robots, const std::vector<ResolvedSpan>& spans, std::size_t t0,
                     std::size_t t1, std::size_t max_robots);

// How many robots a conflict's group may merge: one more than the cap every
// kRecurrencesPerRobot times the same two robots meet again in the same
// kCell x kCell cell, up to kMaxExtraRobots more. Not thread-safe.
class ConflictRecurrence {
 public:
  static constexpr int kRecurrencesPerRobot = 3;
  static constexpr int kMaxExtraRobots = 4;
  static constexpr double kCell = 0.5;
  // The cap for resolving `c` now, counting this time as one more sighting.
  std::size_t capFor(const Conflict& c, std::size_t max_robots);

 private:
  std::map<std::tuple<int, int, long long, long long>, int> seen_;
};

// An individual path for one robot over its roadmap (grown when the query
// fails), shortcut and time-stamped; nothing when none is found in time.
std::optional<Path> individualPath(const CollisionWorld& world, RoadmapSet& roadmaps, const RobotModel& model,
                                   int robot, const Deadline& deadline, std::uint64_t seed);

// Runs ARC with the given hierarchy (tried in order for every subproblem).
PlanResult runArc(const Scenario& scenario, const PlannerSettings& settings, const PlanContext& context,
                  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy);

}  // namespace earc
