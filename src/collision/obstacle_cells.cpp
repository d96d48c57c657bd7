#include "obstacle_cells.hpp"

#include <algorithm>
#include <cmath>

namespace earc {

// A cell is marked when some bound's cell range along both axes takes it
// in. IEEE subtraction and multiplication by a positive number round
// monotonically, so a point inside a bound and inside a query box lies in a
// cell of both ranges: a box whose range holds no marked cell meets no
// bound, with no tolerance needed.
ObstacleCells::ObstacleCells(const std::vector<geo::Aabb>& bounds, std::size_t max_cells) {
  geo::Aabb all;
  for (const geo::Aabb& b : bounds) all.expand(b);
  if (bounds.empty() || !std::isfinite(all.lo.x) || !std::isfinite(all.lo.y) || !std::isfinite(all.hi.x) ||
      !std::isfinite(all.hi.y))
    return;
  const double w = std::max(all.hi.x - all.lo.x, 1e-9);
  const double hgt = std::max(all.hi.y - all.lo.y, 1e-9);
  const double h = std::sqrt(w * hgt / static_cast<double>(std::max<std::size_t>(max_cells, 1)));
  origin_ = all.lo;
  inv_h_ = 1.0 / h;
  // floor + 1: every point of the bounds lies in a cell below nx_ (ny_), so
  // clamping only ever moves points outside every bound.
  nx_ = static_cast<int>(std::min(std::floor(w * inv_h_) + 1.0, 32768.0));
  ny_ = static_cast<int>(std::min(std::floor(hgt * inv_h_) + 1.0, 32768.0));
  // Marks by a 2-D difference array, then two prefix passes give each
  // cell's count; a third pair of passes makes the summed-area table.
  const auto stride = static_cast<std::size_t>(nx_) + 1;
  std::vector<std::int32_t> diff(stride * (static_cast<std::size_t>(ny_) + 1), 0);
  for (const geo::Aabb& b : bounds) {
    const int x0 = std::max(cell(b.lo.x, origin_.x, nx_), 0), x1 = std::min(cell(b.hi.x, origin_.x, nx_), nx_ - 1);
    const int y0 = std::max(cell(b.lo.y, origin_.y, ny_), 0), y1 = std::min(cell(b.hi.y, origin_.y, ny_), ny_ - 1);
    if (x0 > x1 || y0 > y1) continue;
    auto at = [&](int x, int y) -> std::int32_t& { return diff[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)]; };
    ++at(x0, y0);
    --at(x1 + 1, y0);
    --at(x0, y1 + 1);
    ++at(x1 + 1, y1 + 1);
  }
  sums_.assign(stride * (static_cast<std::size_t>(ny_) + 1), 0);
  std::vector<std::int32_t> row(stride, 0);  // running column sums of diff: the cells' counts
  for (int y = 0; y < ny_; ++y) {
    std::int32_t count = 0;
    std::uint32_t marked_in_row = 0;
    for (int x = 0; x < nx_; ++x) {
      count += diff[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)];
      row[static_cast<std::size_t>(x)] += count;
      marked_in_row += row[static_cast<std::size_t>(x)] > 0 ? 1u : 0u;
      // sums_(x+1, y+1) = cells marked in [0, x] x [0, y]
      sums_[static_cast<std::size_t>(y + 1) * stride + static_cast<std::size_t>(x + 1)] =
          sums_[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x + 1)] + marked_in_row;
    }
  }
}

int ObstacleCells::cell(double v, double o, int n) const {
  const double c = std::floor((v - o) * inv_h_);
  if (c < 0.0) return -1;
  if (c >= static_cast<double>(n)) return n;
  return static_cast<int>(c);
}

bool ObstacleCells::mayMeet(const geo::Aabb& box) const {
  if (nx_ == 0) return false;
  if (!(std::isfinite(box.lo.x) && std::isfinite(box.lo.y) && std::isfinite(box.hi.x) && std::isfinite(box.hi.y)))
    return true;
  const int x0 = std::max(cell(box.lo.x, origin_.x, nx_), 0), x1 = std::min(cell(box.hi.x, origin_.x, nx_), nx_ - 1);
  const int y0 = std::max(cell(box.lo.y, origin_.y, ny_), 0), y1 = std::min(cell(box.hi.y, origin_.y, ny_), ny_ - 1);
  if (x0 > x1 || y0 > y1) return false;
  const auto stride = static_cast<std::size_t>(nx_) + 1;
  auto s = [&](int x, int y) { return sums_[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)]; };
  return s(x1 + 1, y1 + 1) - s(x0, y1 + 1) - s(x1 + 1, y0) + s(x0, y0) != 0;
}

}  // namespace earc
