// Ctrl-C for the command-line programs: SIGINT and SIGTERM set a stop flag
// that planning watches (PlanContext::stop) instead of ending the process.
#pragma once

#include <csignal>

#include "earc/util/deadline.hpp"

namespace earc::cli {

// While alive, SIGINT and SIGTERM set stopFlag() (cleared when made), the
// first remembered; a repeat ends the process unless `repeats` is Caught.
// Then restores the handlers (Caught, after a stop: ignores both). One at a time.
class StopSignals {
 public:
  enum class Repeats { EndProcess, Caught };
  // What a stop signal does to a blocking system call: Restart it, or
  // Interrupt it (EINTR) and make wakeFd() readable, for a poll loop.
  enum class Blocking { Restart, Interrupt };
  // Throws std::runtime_error when the wake pipe cannot be made.
  explicit StopSignals(Repeats repeats = Repeats::EndProcess, Blocking blocking = Blocking::Restart);
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  const StopFlag& flag() const;
  // The signal that set the flag (SIGINT or SIGTERM), 0 while none came.
  int signal() const;
  // "SIGINT", "SIGTERM", or "" while none came.
  const char* signalName() const;
  // The conventional exit status after the signal: 128 + its number.
  int exitCode() const { return 128 + signal(); }
  // With Blocking::Interrupt, a non-blocking descriptor that turns readable
  // once a stop signal came (never drained); else -1.
  int wakeFd() const { return wake_read_; }

 private:
  struct sigaction old_int_{}, old_term_{};
  Repeats repeats_;
  int wake_read_ = -1;
};

// The flag StopSignals sets, which a program may also set (or clear) to
// stop its own work, as earc-bench does on an error. Thread-safe.
StopFlag& stopFlag();

}  // namespace earc::cli
