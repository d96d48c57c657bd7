// Ctrl-C for the command-line programs: SIGINT and SIGTERM set a stop flag
// that planning watches (PlanContext::stop) instead of ending the process.
#pragma once

#include <csignal>

#include "earc/util/deadline.hpp"

namespace earc::cli {

// While alive, SIGINT and SIGTERM set stopFlag() (cleared when made) and
// the first is remembered; a second of the same kind ends the process
// unless `repeats` is Caught. Restores the previous handlers. One at a time.
class StopSignals {
 public:
  enum class Repeats { EndProcess, Caught };
  explicit StopSignals(Repeats repeats = Repeats::EndProcess);
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

 private:
  struct sigaction old_int_{}, old_term_{};
};

// The flag StopSignals sets, which a program may also set (or clear) to
// stop its own work, as earc-bench does on an error. Thread-safe.
StopFlag& stopFlag();

}  // namespace earc::cli
