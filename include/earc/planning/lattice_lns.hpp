// Shortening a crowd solver's plan on its own roadmap: large-neighbourhood
// search as in MAPF-LNS (Li et al., IJCAI 2021): a few robots at a time are
// replanned by space-time A* against everyone else's steps, and the new
// paths are kept when their sum of costs is lower.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "earc/planning/crowd_roadmap.hpp"
#include "earc/planning/plan_stats.hpp"
#include "earc/scene/path.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

// Roadmap steps until each robot is at its goal for good, summed.
long long latticeSumOfCosts(const CrowdRoadmap& roadmap, const std::vector<std::vector<int>>& configs);

// Shortens configs (conflict-free steps, starts to goals) until the deadline or
// max_rounds; the result is again such steps, never costlier. Returns stats
// (sums of costs, neighbourhoods tried and kept). Deterministic per seed and rounds.
LatticeRefineStats refineOnLattice(const CrowdRoadmap& roadmap, std::vector<std::vector<int>>& configs,
                                   const Deadline& deadline, std::uint64_t seed, int max_rounds = 1 << 30);

// refineOnLattice, then the same search with diagonal steps too (in ticks of half
// a step): the plan as time-stamped paths, never costlier; stats as refineOnLattice's
// (in ticks). Nothing when the roadmap cannot take diagonals (tick_search.hpp).
std::optional<std::vector<Path>> refineWithDiagonals(const CrowdRoadmap& roadmap,
                                                     const std::vector<std::vector<int>>& configs,
                                                     const Deadline& deadline, std::uint64_t seed,
                                                     const std::vector<std::vector<double>>& starts,
                                                     const std::vector<std::vector<double>>& goals,
                                                     LatticeRefineStats& stats, int max_rounds = 1 << 30);

}  // namespace earc
