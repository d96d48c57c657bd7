// Running one program as a child process under limits, so that whatever it
// does (crash, hang, run out of memory) is a measured outcome and never the
// benchmark's end: fork + exec, its own process group, a wall-clock limit
// after which the group gets SIGKILL, an address-space limit
// (RLIMIT_AS), and death with the thread that started it (PR_SET_PDEATHSIG),
// so a benchmark killed with SIGKILL leaves no planner behind.
#pragma once

#include <atomic>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace earc::bench {

// Test-only faults the child can be told to commit instead of running its
// program, to exercise the failure paths (see EARC_BENCH_FAULT in run.cpp).
enum class ChildFault { None, Crash, Hang };

struct ChildSpec {
  std::vector<std::string> argv;  // argv[0] is the program's path
  std::string stdout_path;        // where the child's stdout/stderr go
  std::string stderr_path;        // (empty: /dev/null, or ours with inherit_output)
  double wall_limit_s = 60.0;
  std::size_t memory_limit_mb = 0;  // 0: no limit
  ChildFault fault = ChildFault::None;
  bool inherit_output = false;    // empty paths mean our own stdout/stderr
};

struct ChildOutcome {
  bool started = false;           // false: fork failed (error says why)
  std::optional<int> exit_code;   // when it exited
  std::optional<int> signal;      // when a signal ended it
  bool killed_at_limit = false;   // we sent SIGKILL at the wall-clock limit
  bool cancelled = false;         // we sent SIGKILL because of `cancel`
  double wall_s = 0.0;
  long peak_rss_kb = 0;           // wait4's ru_maxrss
  std::string error;
};

// Runs the child to its end. Polls `cancel` (when given; the programs pass
// cli::stopFlag()) and kills the child once it is set. Thread-safe.
ChildOutcome runChild(const ChildSpec& spec, const std::atomic<bool>* cancel = nullptr);

// The last non-empty line of a text file (at most max_chars), "" when none.
std::string lastLine(const std::string& path, std::size_t max_chars = 300);
// The first non-empty line.
std::string firstLine(const std::string& path, std::size_t max_chars = 300);

// "SIGSEGV", "SIGKILL", ... ("signal" for the rest).
const char* signalName(int sig);

// Why a child meant to write a result did not, in one line ("killed at the
// wall-clock limit (N s)", "crashed: ...", "exit N: <last stderr line>",
// "interrupted"); "" when it exited 0 or 1. `err_path`: its stderr file.
std::string childFailure(const ChildOutcome& outcome, const ChildSpec& spec, const std::string& err_path);

// The directory holding the running executable (for finding earc-plan next
// to earc-bench).
std::string executableDir();

}  // namespace earc::bench
