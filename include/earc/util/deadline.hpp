// A wall-clock deadline that planners poll.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <limits>

namespace earc {

// A process-wide stop request: once set, every Deadline reads as expired
// (remaining() 0), so a planner in flight winds down as if its time limit
// had passed. Set from a signal handler by `earc-plan serve` (a lock-free
// atomic store is async-signal-safe); cleared before the next request.
inline std::atomic<bool> g_stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);
inline void requestStop() noexcept { g_stop_requested.store(true, std::memory_order_relaxed); }
inline void clearStopRequest() noexcept { g_stop_requested.store(false, std::memory_order_relaxed); }
inline bool stopRequested() noexcept { return g_stop_requested.load(std::memory_order_relaxed); }

class Deadline {
 public:
  using Clock = std::chrono::steady_clock;
  Deadline() : end_(Clock::time_point::max()) {}
  explicit Deadline(double seconds_from_now)
      : end_(seconds_from_now >= 1e9 ? Clock::time_point::max()
                                     : Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                          std::chrono::duration<double>(seconds_from_now))) {}
  bool expired() const { return stopRequested() || (end_ != Clock::time_point::max() && Clock::now() >= end_); }
  double remaining() const {
    if (stopRequested()) return 0.0;
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

// A deadline read where the work is: at the first call, then once per
// `work_per_read` units of work (bodies placed, say), so that a loop of
// cheap steps pays next to nothing for it while one of costly steps (an
// arm of thousands of links) notices the deadline within a step or two.
// Once expired it stays so.
class DeadlinePoll {
 public:
  DeadlinePoll(const Deadline& deadline, std::size_t work_per_read)
      : deadline_(deadline), per_read_(work_per_read), owed_(work_per_read) {}
  // Counts `work` more units done; whether the deadline has expired (as
  // of the last read of the clock).
  bool expired(std::size_t work) {
    if (expired_) return true;
    owed_ += work;
    if (owed_ < per_read_) return false;
    owed_ = 0;
    expired_ = deadline_.expired();
    return expired_;
  }
  // Whether an earlier call found the deadline expired (no clock read).
  bool seenExpired() const { return expired_; }

 private:
  Deadline deadline_;
  std::size_t per_read_;
  std::size_t owed_;
  bool expired_ = false;
};

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace earc
