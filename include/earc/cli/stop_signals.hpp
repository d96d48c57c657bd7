// Ctrl-C for the command-line programs: SIGINT and SIGTERM set a stop flag
// that planning watches (PlanContext::stop) instead of ending the process.
#pragma once

#include <csignal>

#include "earc/util/deadline.hpp"

namespace earc::cli {

// While alive, the first SIGINT or SIGTERM sets flag() and is remembered;
// a second one of the same kind ends the process as usual. Restores the
// previous handlers when it ends. One at a time per process.
class StopSignals {
 public:
  StopSignals();
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

}  // namespace earc::cli
