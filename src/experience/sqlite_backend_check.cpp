// The SQLite engine's structural check of its file in a background
// thread (StoreOptions::check_in_background): started at open, awaited by
// every write, taken over by the caller when the thread gets no CPU.
#include <pthread.h>
#include <sched.h>

#include <chrono>
#include <condition_variable>

#include "earc/experience/schema.hpp"
#include "sqlite_backend.hpp"

namespace earc::exp {

struct SqliteBackend::BackgroundCheck {
  std::thread thread;
  std::mutex mutex;  // the fields below
  std::condition_variable ended;
  bool done = false;
  bool passed = false;
  bool stopped = false;    // asked to stop: its verdict is not wanted
  sqlite3* db = nullptr;   // its connection while open, for sqlite3_interrupt
  std::exception_ptr error;
};

namespace {

// Asks `check` to stop: interrupts its quick_check, if running; it ends
// without a verdict.
void stopCheck(SqliteBackend::BackgroundCheck& check) {
  std::lock_guard l(check.mutex);
  check.stopped = true;
  if (check.db) sqlite3_interrupt(check.db);
}

// Waits for `check` to end, at most `wait`; whether it has.
bool awaitEnd(SqliteBackend::BackgroundCheck& check, std::chrono::milliseconds wait) {
  std::unique_lock l(check.mutex);
  return check.ended.wait_for(l, wait, [&] { return check.done; });
}

// Stops `check`, whose verdict is no longer wanted, and lets its thread
// go: given an ordinary priority where that is allowed (root), so that a
// starved idle-class thread gets the time to notice, and joined if it
// ends within `wait`, else detached, holding its own state.
void abandonCheck(SqliteBackend::BackgroundCheck& check, std::chrono::milliseconds wait) {
  stopCheck(check);
  sched_param normal{};
  pthread_setschedparam(check.thread.native_handle(), SCHED_OTHER, &normal);
  if (awaitEnd(check, wait))
    check.thread.join();
  else
    check.thread.detach();
}

}  // namespace

void SqliteBackend::dropCheck() {
  if (!check_) return;
  abandonCheck(*check_, std::chrono::milliseconds(10));
  check_.reset();
}

namespace {

// The CPU time a thread has used (ns), or -1 where it cannot be read.
double threadCpuNs(std::thread& t) {
  clockid_t clock;
  timespec ts{};
  if (pthread_getcpuclockid(t.native_handle(), &clock) != 0 || clock_gettime(clock, &ts) != 0) return -1;
  return static_cast<double>(ts.tv_sec) * 1e9 + static_cast<double>(ts.tv_nsec);
}

void runQuickCheck(const std::string& path, const ConnectionSettings& settings,
                   SqliteBackend::BackgroundCheck* publish_to) {
  // A connection of its own: the store's serves the planner meanwhile.
  Connection c(path, OpenMode::ReadOnly, settings);
  if (publish_to) {
    std::lock_guard l(publish_to->mutex);
    if (publish_to->stopped) return;
    publish_to->db = c.handle();
  }
  struct Unpublish {
    SqliteBackend::BackgroundCheck* check;
    ~Unpublish() {
      if (!check) return;
      std::lock_guard l(check->mutex);
      check->db = nullptr;
    }
  } unpublish{publish_to};
  c.retryWhileBusy([&] { c.requireQuickCheck(); });
}

}  // namespace

bool SqliteBackend::checkRunning() const {
  if (!check_) return false;
  std::lock_guard l(check_->mutex);
  return !check_->done;
}

ConnectionSettings SqliteBackend::checkSettings() const {
  ConnectionSettings settings = core_.options.connection;
  settings.own_application_id = kApplicationId;  // query_only, as open()'s
  return settings;
}

void SqliteBackend::startCheck() {
  check_ = std::make_shared<BackgroundCheck>();
  check_->thread = std::thread([check = check_, path = core_.path, settings = checkSettings()] {
    // Spare cores only: under full load a normal thread takes time from
    // the plans, its own and the others' (docs/performance-log.md). An
    // idle-class thread runs when a core would otherwise idle. On a machine kept busy by other processes
    // it gets no time at all, not even while awaitCheck() waits for it:
    // finishCheck then runs the check itself (see there).
    // Best effort: where the policy is refused, the check runs anyway.
    // Then it yields: the rest of the slice it was started with is the
    // planner's, not the idle class's, and would be spent on the check.
    sched_param idle{};
    if (pthread_setschedparam(pthread_self(), SCHED_IDLE, &idle) == 0) sched_yield();
    std::exception_ptr error;
    bool passed = false;
    try {
      runQuickCheck(path, settings, check.get());
      passed = true;
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard l(check->mutex);
      // Stopped (interrupted, or never begun): finishCheck checks anew.
      check->passed = passed && !check->stopped;
      if (!check->stopped) check->error = error;
      check->done = true;
    }
    check->ended.notify_all();
  });
}

void SqliteBackend::finishCheck() {
  if (check_) {
    std::shared_ptr<BackgroundCheck> check = std::move(check_);
    // Waits while the check gets CPU time. One that got almost none over
    // a wait is starved by other processes (its idle class comes after
    // every busy one) and could keep a short plan waiting for seconds
    // (docs/performance-log.md). It is stopped, and the check runs here at
    // this thread's priority (abandonCheck). A stopped check has no
    // verdict, passed or failed.
    constexpr auto kWait = std::chrono::milliseconds(10);
    bool ended = false, starved = false;
    while (!ended && !starved) {
      const double before = threadCpuNs(check->thread);
      ended = awaitEnd(*check, kWait);
      const double after = threadCpuNs(check->thread);
      starved = !ended && before >= 0 && after >= 0 && after - before < 0.2 * 1e6 * static_cast<double>(kWait.count());
    }
    bool passed = false;
    if (starved) {
      abandonCheck(*check, kWait);
      check_run_ = ExperienceStore::CheckRun::TakenOver;
    } else {
      check->thread.join();
      passed = check->passed;
      check_error_ = check->error;
    }
    if (!passed && !check_error_) try {
        runQuickCheck(core_.path, checkSettings(), nullptr);
      } catch (...) {
        check_error_ = std::current_exception();
      }
  }
}

void SqliteBackend::joinCheck() {
  finishCheck();
  if (check_error_) {
    check_error_reported_ = true;
    std::rethrow_exception(check_error_);
  }
}

}  // namespace earc::exp
