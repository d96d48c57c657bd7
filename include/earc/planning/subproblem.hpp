// A local subproblem cut out of a multi-robot plan around a conflict
// (E-ARC, "Subproblem Creation"): only the robots involved, a time window
// around the conflict, and a region of their configuration spaces.
#pragma once

#include <cstddef>
#include <vector>

#include "earc/geometry/shapes.hpp"
#include "earc/scene/path.hpp"

namespace earc {

// Per-robot configuration-space box in which local solvers plan.
struct ConfigBox {
  std::vector<double> lo;
  std::vector<double> hi;
  bool contains(const double* q) const;
  bool operator==(const ConfigBox&) const = default;
};

struct Subproblem {
  std::vector<int> robots;                  // scenario indices, ascending
  std::vector<std::vector<double>> starts;  // local query, one per robot
  std::vector<std::vector<double>> goals;
  std::vector<ConfigBox> region;            // one per robot
  geo::Aabb workspace_region;               // the region's footprint in the plane
  std::size_t t_start = 0;                  // global steps replaced: [t_start, t_end]
  std::size_t t_end = 0;
  int expansions = 0;                       // times the window was grown
  bool whole_problem = false;               // the window and region cover everything
};

// A local solution: one path per subproblem robot, all of the same length,
// from the local starts to the local goals.
struct LocalSolution {
  std::vector<Path> paths;
  std::size_t length() const { return paths.empty() ? 0 : paths.front().size(); }
};

}  // namespace earc
