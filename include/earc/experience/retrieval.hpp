// The planner's side of the experience store (paper, "Database Retrieval
// and Subproblem Planning"): canonicalize a subproblem, retrieve the k
// closest stored solutions of its class, map them back into the
// subproblem's frame and robot order; and learn a solved subproblem.
//
//   auto candidates = exp::retrieveCandidates(store, robots, starts, goals, settings.db.k);
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

// Up to k stored solutions nearest the subproblem (the `skip` nearest left
// out), mapped to its frame, robot order and resolution; empty when the
// robots form no class. Rows they cannot follow go to `unusable`.
std::vector<Candidate> retrieveCandidates(ExperienceStore& store, const std::vector<const RobotModel*>& robots,
                                          const std::vector<std::vector<double>>& starts,
                                          const std::vector<std::vector<double>>& goals, std::size_t k,
                                          std::size_t skip = 0, std::vector<std::int64_t>* unusable = nullptr);

// The most states fitResolution makes of a stored solution: far above
// what the builder stores, split by the ratio of two resolutions.
inline constexpr std::size_t kMaxFittedStates = 100'000;

// The paths with every step some robot cannot make at its resolution split
// into as many as the slowest needs. Throws NoStepCountError for a step
// too long for an int count or beyond kMaxFittedStates states.
std::vector<Path> fitResolution(const std::vector<const RobotModel*>& robots, const std::vector<Path>& paths);

// Stores a solved subproblem (paths in its robot order and world frame,
// all of one length); the new id, or nothing for a near duplicate, robots
// of no class, or paths the store cannot hold (stateProblem).
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
