#include "earc/cli/stop_signals.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace earc::cli {

namespace {
StopFlag g_stop{false};
volatile std::sig_atomic_t g_stop_signal = 0;
// The wake pipe's write end (Blocking::Interrupt), -1 without one.
std::atomic<int> g_wake_write{-1};
static_assert(std::atomic<int>::is_always_lock_free);

// Async-signal-safe: lock-free atomics, a sig_atomic_t write and write(2),
// errno kept. SA_RESETHAND (Repeats::EndProcess) puts the default action
// back, so that a second Ctrl-C ends a program that is slow to notice the
// first; a benchmark or the service catches every one, to finish cleanly.
// The byte into the wake pipe wakes a poll loop even when the signal came
// between its check of the flag and its poll.
void onStopSignal(int signo) {
  if (!g_stop_signal) g_stop_signal = signo;
  g_stop.store(true, std::memory_order_relaxed);
  if (const int fd = g_wake_write.load(); fd >= 0) {
    const int saved = errno;
    const char byte = 1;
    [[maybe_unused]] const ssize_t n = ::write(fd, &byte, 1);  // a full pipe is awake already
    errno = saved;
  }
}
}  // namespace

StopSignals::StopSignals(Repeats repeats, Blocking blocking) : repeats_(repeats) {
  g_stop.store(false);
  g_stop_signal = 0;
  if (blocking == Blocking::Interrupt) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC | O_NONBLOCK) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    wake_read_ = fds[0];
    g_wake_write.store(fds[1]);
  }
  struct sigaction sa{};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = (blocking == Blocking::Restart ? SA_RESTART : 0) | (repeats == Repeats::EndProcess ? SA_RESETHAND : 0);
  sigaction(SIGINT, &sa, &old_int_);
  sigaction(SIGTERM, &sa, &old_term_);
}

StopSignals::~StopSignals() {
  // A program that catches every repeat is ending after a stop: a repeat
  // sent a moment late (two Ctrl-C, a supervisor's second SIGTERM) must
  // not kill it in its last destructors, so both stay ignored.
  if (repeats_ == Repeats::Caught && g_stop_signal) {
    struct sigaction ignore{};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    sigaction(SIGINT, &ignore, nullptr);
    sigaction(SIGTERM, &ignore, nullptr);
  } else {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  if (const int fd = g_wake_write.exchange(-1); fd >= 0) ::close(fd);
  if (wake_read_ >= 0) ::close(wake_read_);
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
