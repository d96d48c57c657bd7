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

// The subproblem for a conflict among `robots` at expansion level `level`:
// window initial_window * 2^level steps each side of the conflict, its end
// moved forward until the robots' local goals are apart; per-robot region
// around the local query with a margin that grows with the level; the whole
// problem once the window covers every path and the level is the last.
Subproblem createSubproblem(const Conflict& conflict, const std::vector<int>& robots, int level,
                            const std::vector<const RobotModel*>& models, const std::vector<Path>& paths,
                            const CollisionWorld& world, const PlannerSettings& settings);

// UpdateSolution: replaces steps [t_start, t_end] of each subproblem robot's
// path by its local path; the rest of the path follows (shifted in time when
// the local path is longer than the span it replaces).
void splice(std::vector<Path>& paths, const Subproblem& sub, const LocalSolution& local);

// Adds to `robots` the robots of every span that overlaps steps [t0, t1]
// and shares a robot with the original `robots` (one hop, not transitive),
// skipping a span that would make the group larger than max_robots.
// Returns how many were added.
int mergeOverlapping(std::vector<int>& robots, const std::vector<ResolvedSpan>& spans, std::size_t t0,
                     std::size_t t1, std::size_t max_robots);

// How many robots a conflict's group may merge. Past the cap, an answer
// that undoes a resolved robot's span is accepted, and two groups at the
// cap can then undo each other for ever: in a crowd of 0.8-radius discs,
// E-ARC solved the same two conflicts in turn 14,000 times in 20 s. The
// same conflict found again means its resolution was undone: every
// kRecurrencesPerRobot times it comes back, its group may take one more
// robot, up to kMaxExtraRobots more, so that the robot whose span it keeps
// undoing joins it. The same conflict: the same two robots meeting in the
// same kCell x kCell cell of the plane, at any instant, since every
// resolution shifts the later paths in time (64 discs of radius 0.6: of
// 1,964 conflicts that repeated an earlier one within half a unit and 60
// steps, 324 fell on its instant). Plans whose conflicts do not come back
// this often are unchanged.
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
PlanResult runArc(const Scenario& scenario, const PlannerSettings& settings,
                  std::vector<std::unique_ptr<SubproblemSolver>> hierarchy);

}  // namespace earc
