// A deadline that planners poll: wall-clock time, and budgets within it
// that count seconds or (Deadline::withWorkBudgets) work done.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace earc {

// A stop request that deadlines watch (Deadline::stoppedBy): once set,
// they read as expired. Setting it is async-signal-safe and thread-safe.
using StopFlag = std::atomic<bool>;
static_assert(StopFlag::is_always_lock_free);
// Whether `flag` is given and set. Thread-safe.
inline bool stopSet(const StopFlag* flag) noexcept { return flag && flag->load(std::memory_order_relaxed); }

// Work done on this thread in the collision checks' units: the clock of
// budgets that count work (Deadline::withWorkBudgets). Per thread.
inline thread_local std::uint64_t t_work_done = 0;
inline void countWork(std::size_t units) noexcept { t_work_done += units; }

// Units of work a second of budget stands for when budgets count work:
// about what one core of the machine the defaults were tuned on did.
inline constexpr double kWorkPerBudgetSecond = 2.0e7;

// The work done on this thread so far, in budget seconds. Per thread.
inline double workSecondsDone() noexcept { return static_cast<double>(t_work_done) / kWorkPerBudgetSecond; }

class Deadline {
 public:
  using Clock = std::chrono::steady_clock;
  Deadline() : end_(Clock::time_point::max()) {}
  explicit Deadline(double seconds_from_now)
      : end_(seconds_from_now >= 1e9 ? Clock::time_point::max()
                                     : Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                          std::chrono::duration<double>(seconds_from_now))) {}
  bool expired() const {
    return stopSet(stop_) || workSpent() || (end_ != Clock::time_point::max() && Clock::now() >= end_);
  }
  // This deadline, also expired once *stop is set (null: no stop request).
  Deadline stoppedBy(const StopFlag* stop) const {
    Deadline d = *this;
    d.stop_ = stop;
    return d;
  }
  // Whether a work budget (see capped) has been used up: no clock read.
  bool workSpent() const noexcept { return t_work_done >= work_end_; }
  double remaining() const {
    if (stopSet(stop_)) return 0.0;
    double left = std::numeric_limits<double>::infinity();
    if (work_end_ != kNoWorkEnd)
      left = work_end_ > t_work_done ? static_cast<double>(work_end_ - t_work_done) / kWorkPerBudgetSecond : 0.0;
    if (end_ == Clock::time_point::max()) return left;
    return std::min(left, std::chrono::duration<double>(end_ - Clock::now()).count());
  }
  // This deadline, its capped() budgets counting work done on the calling
  // thread instead of seconds when `on`; its own end stays wall-clock time.
  Deadline withWorkBudgets(bool on) const {
    Deadline d = *this;
    d.work_budgets_ = on;
    return d;
  }
  bool countsWork() const noexcept { return work_budgets_; }
  // The earlier of this deadline and `seconds` from now: seconds of work
  // on this thread when budgets count work.
  Deadline capped(double seconds) const {
    if (work_budgets_) {
      Deadline d = *this;
      const double units = std::max(0.0, seconds) * kWorkPerBudgetSecond;
      if (units < static_cast<double>(kNoWorkEnd - t_work_done))
        d.work_end_ = std::min(work_end_, t_work_done + static_cast<std::uint64_t>(units));
      return d;
    }
    Deadline d(seconds);
    d.work_end_ = work_end_;
    d.stop_ = stop_;
    return d.end_ < end_ ? d : *this;
  }

 private:
  static constexpr std::uint64_t kNoWorkEnd = std::numeric_limits<std::uint64_t>::max();
  Clock::time_point end_;
  std::uint64_t work_end_ = kNoWorkEnd;
  bool work_budgets_ = false;
  const StopFlag* stop_ = nullptr;
};

// A deadline read at the first call, then once per `work_per_read` units of
// work, so cheap loops pay little and costly ones notice within a step or
// two. Once expired it stays so. Not thread-safe.
class DeadlinePoll {
 public:
  DeadlinePoll(const Deadline& deadline, std::size_t work_per_read)
      : deadline_(deadline), per_read_(work_per_read), owed_(work_per_read) {}
  // Counts `work` more units done; whether the deadline has expired (as
  // of the last read of the clock).
  bool expired(std::size_t work) {
    if (expired_) return true;
    countWork(work);
    // A work budget is checked at every call (no clock read), so that it
    // ends at the same work however this poll's reads fall.
    if (deadline_.workSpent()) return expired_ = true;
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
