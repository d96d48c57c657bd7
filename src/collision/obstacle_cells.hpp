// A summed-area table of the cells of a uniform grid that obstacles' bounds
// meet: answers "may any obstacle's bounds meet this box?" in four look-ups.
#pragma once

#include <cstdint>
#include <vector>

#include "earc/geometry/shapes.hpp"

namespace earc {

class ObstacleCells {
 public:
  // A grid of at most about max_cells cells over the bounds of `bounds`.
  // Empty bounds make a table that answers false to every box.
  ObstacleCells(const std::vector<geo::Aabb>& bounds, std::size_t max_cells);

  // False only when no bound given meets box (closed boxes, as
  // geo::Aabb::overlaps); true when one may. Non-finite boxes give true. Thread-safe.
  bool mayMeet(const geo::Aabb& box) const;

  int columns() const { return nx_; }
  int rows() const { return ny_; }

 private:
  // Cell index of coordinate v along an axis of origin o and n cells,
  // clamped to [-1, n] (outside the grid on either side).
  int cell(double v, double o, int n) const;

  geo::Vec2 origin_{};
  double inv_h_ = 1.0;
  int nx_ = 0, ny_ = 0;
  // (nx_ + 1) x (ny_ + 1) prefix sums of the marked cells, row-major.
  std::vector<std::uint32_t> sums_;
};

}  // namespace earc
