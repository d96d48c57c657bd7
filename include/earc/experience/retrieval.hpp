// The planner's side of the experience store (paper, "Database Retrieval
// and Subproblem Planning"): canonicalize a subproblem, retrieve the k
// closest stored solutions of its class, map them back into the
// subproblem's frame and robot order; and learn a solved subproblem.
//
//   auto candidates = exp::retrieveCandidates(store, robots, starts, goals, settings.db_k);
//   for (auto& c : candidates) { ... validate / connect / repair c.paths ...
//                                store.recordUse(c.id, resolved); }
//   if (solved_from_scratch) exp::learn(store, robots, local.paths, seconds, exp::Source::Planner);
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "earc/experience/store.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"

namespace earc::exp {

// Planner inserts closer than this in key space (units for mobile robots,
// radians for arms) to a stored entry are skipped: about one resolution
// step, below which two subproblems are the same to the solver.
inline constexpr double kNearDuplicateEps = 0.05;

struct Candidate {
  std::int64_t id = 0;      // for recordUse
  double distance = 0.0;    // key distance to the query
  std::vector<Path> paths;  // subproblem robot order and world frame
};

// Up to k stored solutions for the subproblem, nearest first, mapped into
// its frame and robot order: each path starts near the robot's start and
// ends near its goal (not exactly; the caller connects them). Empty when
// the robots form no experience class (hasExperienceClass). For a
// symmetric arm pair both role assignments are searched and merged.
// Entries stored under a coarser resolution than the robots' come back
// with their long steps split (fitResolution), never breaking the
// resolution rule. With skip > 0, the k nearest less the `skip` nearest
// (rows not read): the next candidates after a first call with k = skip.
// (For a symmetric pair, a row found under one role assignment before the
// skip can come back under the other after it.) A row the robots cannot
// follow at their resolution (fitResolution throws NoStepCountError) is
// left out, its id put in `unusable` when given.
std::vector<Candidate> retrieveCandidates(ExperienceStore& store, const std::vector<const RobotModel*>& robots,
                                          const std::vector<std::vector<double>>& starts,
                                          const std::vector<std::vector<double>>& goals, std::size_t k,
                                          std::size_t skip = 0, std::vector<std::int64_t>* unusable = nullptr);

// The most states fitResolution makes of a stored solution. Stored ones
// are tens to hundreds of states (at most 287 in a 198-row database the
// builder made, 76 on average), split by the ratio of two scenarios'
// resolutions: this leaves a ratio of 300 to the longest.
inline constexpr std::size_t kMaxFittedStates = 100'000;

// Paths whose consecutive states some robot cannot reach in one step at
// its resolution, with every such step split into as many as the slowest
// robot needs (all robots move together, as in the coupled solver's time
// stamping). Paths that already fit are returned unchanged. Throws
// NoStepCountError for a step too long for an int count, or when the
// split paths would hold more than kMaxFittedStates states.
std::vector<Path> fitResolution(const std::vector<const RobotModel*>& robots, const std::vector<Path>& paths);

// Stores a solved subproblem: paths in subproblem robot order and world
// frame, all of one length (a LocalSolution). Its starts and goals are the
// paths' endpoints. Returns the new id, or nothing for a near duplicate,
// robots that form no class, or paths beyond what the store holds
// (stateProblem).
std::optional<std::int64_t> learn(ExperienceStore& store, const std::vector<const RobotModel*>& robots,
                                  const std::vector<Path>& paths, double solve_time_s, Source source = Source::Planner,
                                  double near_duplicate_eps = kNearDuplicateEps);

// A solved subproblem waiting to be learned.
struct Solved {
  std::vector<const RobotModel*> robots;
  std::vector<Path> paths;  // subproblem robot order and world frame
  double solve_time_s = 0.0;
};

// learn() for several solutions in ONE transaction (one fsync instead of
// one per solution). Entries whose robots form no class are skipped.
// Returns how many were stored.
std::size_t learnAll(ExperienceStore& store, const std::vector<Solved>& solved, Source source = Source::Planner,
                     double near_duplicate_eps = kNearDuplicateEps);

}  // namespace earc::exp
