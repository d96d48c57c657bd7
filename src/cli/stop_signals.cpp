#include "earc/cli/stop_signals.hpp"

#include <signal.h>

namespace earc::cli {

namespace {
StopFlag g_stop{false};
volatile std::sig_atomic_t g_stop_signal = 0;

// Async-signal-safe: a lock-free atomic store and a sig_atomic_t write.
// SA_RESETHAND (Repeats::EndProcess) puts the default action back, so that
// a second Ctrl-C ends a program that is slow to notice the first; a
// benchmark catches every one, to stop its children and write its summary.
void onStopSignal(int signo) {
  if (!g_stop_signal) g_stop_signal = signo;
  g_stop.store(true, std::memory_order_relaxed);
}
}  // namespace

StopSignals::StopSignals(Repeats repeats) {
  g_stop.store(false);
  g_stop_signal = 0;
  struct sigaction sa{};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART | (repeats == Repeats::EndProcess ? SA_RESETHAND : 0);
  sigaction(SIGINT, &sa, &old_int_);
  sigaction(SIGTERM, &sa, &old_term_);
}

StopSignals::~StopSignals() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
}

const StopFlag& StopSignals::flag() const { return g_stop; }

StopFlag& stopFlag() { return g_stop; }

int StopSignals::signal() const { return g_stop_signal; }

const char* StopSignals::signalName() const {
  switch (g_stop_signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "";
  }
}

}  // namespace earc::cli
