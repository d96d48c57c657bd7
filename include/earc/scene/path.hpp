// Time-stamped paths: states[t] is a robot's configuration at step t; after
// its last state a robot stays there.
#pragma once

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <span>
#include <vector>

namespace earc {

// A robot's path, stored flat (state t occupies [t*dim, (t+1)*dim)).
class Path {
 public:
  Path() = default;
  explicit Path(int dim) : dim_(dim) {}

  int dim() const { return dim_; }
  std::size_t size() const { return dim_ == 0 ? 0 : data_.size() / static_cast<std::size_t>(dim_); }
  bool empty() const { return data_.empty(); }

  // State t; t past the end answers the last state (the robot waits there).
  const double* at(std::size_t t) const {
    assert(!empty());
    std::size_t n = size();
    return data_.data() + (t < n ? t : n - 1) * static_cast<std::size_t>(dim_);
  }
  std::span<const double> state(std::size_t t) const { return {at(t), static_cast<std::size_t>(dim_)}; }
  double* mutableAt(std::size_t t) { return data_.data() + t * static_cast<std::size_t>(dim_); }
  const double* back() const { return at(size() - 1); }

  void push(const double* q) { data_.insert(data_.end(), q, q + dim_); }
  void push(std::span<const double> q) { push(q.data()); }
  void append(const Path& o, std::size_t from = 0) {
    assert(o.dim_ == dim_);
    if (from < o.size()) data_.insert(data_.end(), o.data_.begin() + static_cast<std::ptrdiff_t>(from * dim_), o.data_.end());
  }
  void clear() { data_.clear(); }
  // Drops copies of the last state at the end: the robot waits there
  // anyway, and a solution's sum of costs counts a robot's steps only
  // until it last moves.
  void dropTrailingWaits() {
    const auto d = static_cast<std::size_t>(dim_);
    while (size() > 1 && std::equal(data_.end() - static_cast<std::ptrdiff_t>(d), data_.end(),
                                    data_.end() - static_cast<std::ptrdiff_t>(2 * d)))
      data_.resize(data_.size() - d);
  }
  void reserve(std::size_t n) { data_.reserve(n * static_cast<std::size_t>(dim_)); }

  // Steps [from, to) as a new path.
  Path slice(std::size_t from, std::size_t to) const {
    Path p(dim_);
    for (std::size_t t = from; t < to && t < size(); ++t) p.push(at(t));
    return p;
  }

  const std::vector<double>& raw() const { return data_; }
  std::vector<double>& raw() { return data_; }
  bool operator==(const Path&) const = default;

 private:
  int dim_ = 0;
  std::vector<double> data_;
};

}  // namespace earc
