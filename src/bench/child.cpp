#include "earc/bench/child.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <thread>

#include "earc/util/format.hpp"

namespace earc::bench {

namespace {

// How often a running child is polled: fine enough that the wall time we
// measure is not inflated noticeably, coarse enough to cost nothing.
constexpr auto kPollInterval = std::chrono::milliseconds(5);

// Between fork and exec only async-signal-safe calls: everything the child
// needs is prepared before fork.
[[noreturn]] void becomeChild(char* const* argv, const char* out, const char* err, pid_t parent, rlim_t memory,
                              ChildFault fault) {
  setpgid(0, 0);
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(126);  // the parent died before prctl
  int in = open("/dev/null", O_RDONLY);
  if (in >= 0) dup2(in, STDIN_FILENO);
  if (out) {
    int o = open(out, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (o >= 0) dup2(o, STDOUT_FILENO);
  }
  if (err) {
    int e = open(err, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (e >= 0) dup2(e, STDERR_FILENO);
  }
  if (memory > 0) {
    struct rlimit lim{memory, memory};
    setrlimit(RLIMIT_AS, &lim);
  }
  if (fault == ChildFault::Crash) {
    struct rlimit no_core{0, 0};
    setrlimit(RLIMIT_CORE, &no_core);
    signal(SIGSEGV, SIG_DFL);
    raise(SIGSEGV);
  }
  if (fault == ChildFault::Hang)
    for (;;) pause();
  execv(argv[0], argv);
  const char msg[] = "earc-bench: cannot execute ";
  (void)!write(STDERR_FILENO, msg, sizeof msg - 1);
  (void)!write(STDERR_FILENO, argv[0], strlen(argv[0]));
  (void)!write(STDERR_FILENO, "\n", 1);
  _exit(127);
}

std::string readHead(const std::string& path, std::size_t limit) {
  std::ifstream in(path, std::ios::binary);
  std::string s(limit, '\0');
  in.read(s.data(), static_cast<std::streamsize>(limit));
  s.resize(static_cast<std::size_t>(in.gcount()));
  return s;
}

std::string clip(std::string s, std::size_t max_chars) {
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ')) s.pop_back();
  if (s.size() > max_chars) s = s.substr(0, max_chars) + "...";
  return s;
}

}  // namespace

ChildOutcome runChild(const ChildSpec& spec, const std::atomic<bool>* cancel) {
  ChildOutcome out;
  std::vector<std::string> args = spec.argv;
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string none = spec.inherit_output ? "" : "/dev/null";
  const std::string out_path = spec.stdout_path.empty() ? none : spec.stdout_path;
  const std::string err_path = spec.stderr_path.empty() ? none : spec.stderr_path;
  const rlim_t memory = static_cast<rlim_t>(spec.memory_limit_mb) << 20;
  const pid_t parent = getpid();

  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    out.error = std::string("fork failed: ") + std::strerror(errno);
    return out;
  }
  if (pid == 0)
    becomeChild(argv.data(), out_path.empty() ? nullptr : out_path.c_str(), err_path.empty() ? nullptr : err_path.c_str(),
                parent, memory, spec.fault);
  setpgid(pid, pid);  // also from here, so that the kill below can never miss the group
  out.started = true;

  const auto limit = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(spec.wall_limit_s));
  int status = 0;
  struct rusage usage{};
  for (;;) {
    pid_t r = wait4(pid, &status, WNOHANG, &usage);
    if (r == pid) break;
    if (r < 0 && errno != EINTR) {
      out.error = std::string("wait4 failed: ") + std::strerror(errno);
      break;
    }
    const bool cancel_now = cancel && cancel->load();
    if (std::chrono::steady_clock::now() >= limit || cancel_now) {
      (cancel_now ? out.cancelled : out.killed_at_limit) = true;
      kill(-pid, SIGKILL);
      kill(pid, SIGKILL);
      while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
      }
      break;
    }
    std::this_thread::sleep_for(kPollInterval);
  }
  // Whatever the child left running in its group goes with it.
  kill(-pid, SIGKILL);
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.peak_rss_kb = usage.ru_maxrss;
  if (WIFEXITED(status)) out.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) out.signal = WTERMSIG(status);
  return out;
}

std::string lastLine(const std::string& path, std::size_t max_chars) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::size_t>(in.tellg());
  const std::size_t tail = std::min<std::size_t>(size, 8192);
  in.seekg(static_cast<std::streamoff>(size - tail));
  std::string s(tail, '\0');
  in.read(s.data(), static_cast<std::streamsize>(tail));
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  // A progress bar redraws with \r: the last redraw is the line.
  const std::size_t from = s.find_last_of("\n\r");
  return clip(from == std::string::npos ? s : s.substr(from + 1), max_chars);
}

std::string firstLine(const std::string& path, std::size_t max_chars) {
  std::string s = readHead(path, 8192);
  std::size_t from = s.find_first_not_of("\r\n ");
  if (from == std::string::npos) return "";
  return clip(s.substr(from, s.find_first_of("\r\n", from) - from), max_chars);
}

const char* signalName(int sig) {
  switch (sig) {
    case SIGSEGV: return "SIGSEGV";
    case SIGABRT: return "SIGABRT";
    case SIGKILL: return "SIGKILL";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGTERM: return "SIGTERM";
    case SIGXCPU: return "SIGXCPU";
    default: return "signal";
  }
}

// Why a child that was meant to write a result did not, in one line: ""
// when it exited 0 or 1 (it reports through its output file), else
// "killed at the wall-clock limit (N s)", "crashed: SIGSEGV (11)",
// "exit N: <last line of its stderr>", "interrupted", or why it did not
// start. `err_path` is the child's stderr file.
std::string childFailure(const ChildOutcome& outcome, const ChildSpec& spec, const std::string& err_path) {
  if (outcome.cancelled) return "interrupted";
  if (!outcome.started) return outcome.error;
  if (outcome.killed_at_limit)
    return "killed at the wall-clock limit (" + formatNumber("%.3g", spec.wall_limit_s) + " s)";
  if (outcome.signal)
    return std::string("crashed: ") + signalName(*outcome.signal) + " (" + std::to_string(*outcome.signal) + ")";
  if (outcome.exit_code == 0 || outcome.exit_code == 1) return "";
  const std::string why = lastLine(err_path);
  return "exit " + std::to_string(outcome.exit_code.value_or(-1)) + (why.empty() ? "" : ": " + why);
}

std::string executableDir() {
  char buf[4096];
  ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  std::string p(buf, static_cast<std::size_t>(n));
  return p.substr(0, p.find_last_of('/'));
}

}  // namespace earc::bench
