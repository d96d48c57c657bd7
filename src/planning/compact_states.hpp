// Robots' states at instants along their timed paths, cached for the
// timing searches of compaction (compact.cpp) and of ARC's robot-by-robot
// stamping (arc_restamp.cpp). Internal to src/planning.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "earc/planning/conflict.hpp"
#include "earc/scene/path.hpp"
#include "earc/scene/robot_model.hpp"
#include "earc/util/deadline.hpp"

namespace earc {

// A timed path seen from a later start: its state at local instant k is its
// path's at instant 2 * offset + min(k, horizon).
struct TimedSource {
  const RobotModel* model = nullptr;
  const Path* path = nullptr;  // empty: never asked for
  std::size_t offset = 0;
  std::size_t horizon = std::numeric_limits<std::size_t>::max();
};

// The sources' states at the instants asked for, each filled on first ask (a
// unit of work) in a ring of `slots` instants; a state stays valid until its
// source's slot is refilled. Not thread-safe.
class InstantStates {
 public:
  void assign(std::vector<TimedSource> sources, std::size_t slots) {
    src_ = std::move(sources);
    offset_.clear();
    width_ = 0;
    for (const TimedSource& s : src_) {
      offset_.push_back(width_);
      width_ += static_cast<std::size_t>(s.model->dim());
    }
    slots_ = std::max<std::size_t>(1, slots);
    tag_.assign(slots_ * src_.size(), kNone);
    q_.resize(slots_ * width_);
  }

  // Source b's state at local instant k.
  const double* at(std::size_t b, std::size_t k) {
    const std::size_t slot = k % slots_;
    double* out = q_.data() + slot * width_ + offset_[b];
    std::uint64_t& tag = tag_[slot * src_.size() + b];
    if (tag != k) {
      countWork(1);
      const TimedSource& s = src_[b];
      stateAtInstant(*s.model, *s.path, 2 * s.offset + std::min(k, s.horizon), out);
      tag = k;
    }
    return out;
  }

  // Source b's path changed: its kept states are filled again when asked.
  void forget(std::size_t b) {
    for (std::size_t slot = 0; slot < slots_; ++slot) tag_[slot * src_.size() + b] = kNone;
  }

 private:
  static constexpr std::uint64_t kNone = std::numeric_limits<std::uint64_t>::max();
  std::vector<TimedSource> src_;
  std::vector<std::size_t> offset_;  // of each source's state in a slot's row
  std::size_t width_ = 0, slots_ = 1;
  std::vector<std::uint64_t> tag_;  // [slot * sources + b]: the instant held
  std::vector<double> q_;
};

}  // namespace earc
