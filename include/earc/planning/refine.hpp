// Anytime refinement (`earc-plan plan --refine S`): a valid plan made
// shorter for a budget of time, by shortcutting each robot's timed path
// and by large-neighbourhood search (MAPF-LNS, Li et al. 2021/2022):
// groups of robots replanned in space-time against everyone else's fixed
// paths. A step after any method's plan; off unless asked for.
//
// Sum of costs: over robots, the steps until a robot last moves; makespan:
// the largest. A change is kept only when it lowers one of them and raises
// neither, and only after its new motions were checked against the
// obstacles and against every other robot at every step and midpoint, so
// a valid plan stays valid and never gets costlier.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "earc/collision/collision_world.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/scene/scenario.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

class RoadmapCache;

struct RefineSettings {
  double seconds = 1.0;              // budget, capped by the deadline given (work with its work budgets)
  std::uint64_t seed = 1;            // every random choice derives from it
  std::size_t max_iterations = 0;    // shortcut tries and neighbourhoods together; 0: no limit
  bool shortcuts = true;             // shortcut operator on
  bool lns = true;                   // large-neighbourhood search on
  std::size_t neighbourhood = 8;     // robots replanned together at most
  // The roadmaps the neighbourhoods are replanned on (RoadmapSet).
  int roadmap_samples = 0;
  int roadmap_neighbors = 10;
  std::uint64_t roadmap_seed = 1;
  RoadmapCache* roadmap_cache = nullptr;
};

struct RefineReport {
  std::size_t first_sum_of_costs = 0, first_makespan = 0;
  std::size_t final_sum_of_costs = 0, final_makespan = 0;
  std::size_t lower_bound = 0;       // summed own shortest ways, others ignored (ownPathLowerBounds)
  std::size_t straight_line_bound = 0;  // summed straight-line steps from start to goal
  double final_s = 0.0;              // seconds into refinement when the best plan was found
  double seconds_spent = 0.0;
  std::size_t retimed_steps = 0;      // saved by first retiming every robot along its route (compactPlan)
  std::size_t iterations = 0;
  std::size_t shortcut_tries = 0, shortcut_improvements = 0;
  std::size_t lns_tries = 0, lns_improvements = 0, lns_failed = 0;
  // Each improvement: seconds into refinement, sum of costs, makespan.
  std::vector<std::array<double, 3>> history;
};

// Refines `paths` (a valid plan of `scenario`, trailing waits dropped) in
// place until settings.seconds, max_iterations or the deadline ends it,
// leaving the best found. Not thread-safe on one plan.
RefineReport refinePlan(const Scenario& scenario, const CollisionWorld& world,
                        const std::vector<const RobotModel*>& models, std::vector<Path>& paths,
                        const RefineSettings& settings, const Deadline& deadline = Deadline());

}  // namespace earc
