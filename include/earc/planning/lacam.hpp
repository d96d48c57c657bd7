// The crowd solver: LaCAM (Okumura, AAAI 2023 and IJCAI 2023), a depth-first
// search over configurations (one vertex per robot) whose successors come
// from PIBT (Okumura et al., AIJ 2022) under constraints that a low-level
// search adds robot by robot, on a CrowdRoadmap with its conflicts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "earc/planning/crowd_roadmap.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

struct LacamResult {
  bool solved = false;
  // configs[t][i]: robot i's vertex after t steps; configs[0] the starts,
  // the last the goals. Consecutive configurations are conflict-free steps.
  std::vector<std::vector<int>> configs;
  std::size_t nodes = 0;        // configurations generated
  std::size_t expansions = 0;   // successor generations tried
  bool timed_out = false;       // the deadline ended the search
  long long spread_meetings = 0;  // meetings left between the guiding ways
  std::size_t restarts = 0;     // searches begun anew with other random choices
  std::string why;              // why not solved
};

// Searches for a sequence of conflict-free steps taking every robot from its
// start to its goal, restarting after first_restart expansions (0: 4 a vertex), twice
// that next. Complete: unsolved only when there is none or the deadline expires. Same seed, same result.
LacamResult solveLacam(const CrowdRoadmap& roadmap, const Deadline& deadline, std::uint64_t seed,
                       std::size_t first_restart = 0);

}  // namespace earc
