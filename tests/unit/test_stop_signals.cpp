// cli::StopSignals: a stop signal sets the flag and is remembered, the
// handlers are put back afterwards, and with Blocking::Interrupt the wake
// descriptor turns readable and a blocking read is interrupted.
#include <doctest/doctest.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <string>
#include <cerrno>
#include <csignal>
#include <chrono>
#include <thread>

#include "earc/cli/stop_signals.hpp"

using namespace earc;

namespace {

bool readableNow(int fd) {
  pollfd p{fd, POLLIN, 0};
  return ::poll(&p, 1, 0) == 1 && (p.revents & POLLIN);
}

using Handler = void (*)(int);

Handler currentHandler(int signo) {
  struct sigaction now{};
  sigaction(signo, nullptr, &now);
  return now.sa_handler;
}

// Leaves the process-wide flag clear for the tests after, as it found it.
struct ClearStopAfter {
  ~ClearStopAfter() { cli::stopFlag().store(false); }
};

}  // namespace

TEST_CASE("stop signals: a signal sets the flag, the first is remembered, handlers are put back") {
  ClearStopAfter clear;
  const Handler before = currentHandler(SIGTERM);
  {
    cli::StopSignals signals(cli::StopSignals::Repeats::Caught);
    CHECK(!signals.flag().load());
    CHECK(signals.signal() == 0);
    CHECK(std::string(signals.signalName()).empty());
    CHECK(signals.wakeFd() == -1);
    CHECK((currentHandler(SIGTERM) != before));
    REQUIRE(::raise(SIGTERM) == 0);
    CHECK(signals.flag().load());
    CHECK(&signals.flag() == &cli::stopFlag());
    CHECK(signals.signal() == SIGTERM);
    CHECK(std::string(signals.signalName()) == "SIGTERM");
    CHECK(signals.exitCode() == 128 + SIGTERM);
    REQUIRE(::raise(SIGINT) == 0);  // caught too; the first stays the one remembered
    CHECK(signals.signal() == SIGTERM);
  }
  // After a stop, a late repeat must not end the program in its last steps.
  CHECK((currentHandler(SIGTERM) == SIG_IGN));
  CHECK((currentHandler(SIGINT) == SIG_IGN));
  REQUIRE(::raise(SIGINT) == 0);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, before);
  // Without a stop, the handlers are put back.
  cli::stopFlag().store(false);
  {
    cli::StopSignals quiet(cli::StopSignals::Repeats::Caught);
    CHECK((currentHandler(SIGTERM) != before));
  }
  CHECK((currentHandler(SIGTERM) == before));
  // A new one starts clear.
  cli::StopSignals again(cli::StopSignals::Repeats::Caught);
  CHECK(!again.flag().load());
  CHECK(again.signal() == 0);
}

TEST_CASE("stop signals: Blocking::Interrupt wakes a poll loop and interrupts a blocking read") {
  ClearStopAfter clear;
  cli::StopSignals signals(cli::StopSignals::Repeats::Caught, cli::StopSignals::Blocking::Interrupt);
  REQUIRE(signals.wakeFd() >= 0);
  CHECK(!readableNow(signals.wakeFd()));
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  // SIGINT at the reading thread until its read returns: one of them comes
  // while it blocks, whenever the read starts.
  std::atomic<bool> done{false};
  const pthread_t reader = ::pthread_self();
  std::thread sender([&] {
    while (!done.load()) {
      ::pthread_kill(reader, SIGINT);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  char byte = 0;
  const ssize_t n = ::read(fds[0], &byte, 1);  // nothing is ever written: only a signal ends it
  const int err = errno;
  done.store(true);
  sender.join();
  CHECK(n == -1);
  CHECK(err == EINTR);
  CHECK(signals.flag().load());
  CHECK(signals.signal() == SIGINT);
  CHECK(readableNow(signals.wakeFd()));
  ::close(fds[0]);
  ::close(fds[1]);
}
