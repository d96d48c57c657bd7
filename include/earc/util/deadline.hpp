// A wall-clock deadline that planners poll.
#pragma once

#include <chrono>
#include <limits>

namespace earc {

class Deadline {
 public:
  using Clock = std::chrono::steady_clock;
  Deadline() : end_(Clock::time_point::max()) {}
  explicit Deadline(double seconds_from_now)
      : end_(seconds_from_now >= 1e9 ? Clock::time_point::max()
                                     : Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                          std::chrono::duration<double>(seconds_from_now))) {}
  bool expired() const { return end_ != Clock::time_point::max() && Clock::now() >= end_; }
  double remaining() const {
    if (end_ == Clock::time_point::max()) return std::numeric_limits<double>::infinity();
    return std::chrono::duration<double>(end_ - Clock::now()).count();
  }
  // The earlier of this deadline and `seconds` from now.
  Deadline capped(double seconds) const {
    Deadline d(seconds);
    return d.end_ < end_ ? d : *this;
  }

 private:
  Clock::time_point end_;
};

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace earc
