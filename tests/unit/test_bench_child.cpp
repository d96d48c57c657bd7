// Child processes under limits: exit codes, crashes, hangs killed at the
// wall-clock limit, output captured.
#include <doctest/doctest.h>

#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "earc/bench/child.hpp"

using namespace earc::bench;

namespace {

std::string temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()))).string();
}

ChildSpec shell(const std::string& script, double wall = 10.0) {
  ChildSpec s;
  s.argv = {"/bin/sh", "-c", script};
  s.wall_limit_s = wall;
  return s;
}

}  // namespace

TEST_CASE("a child's exit code, output and peak memory come back") {
  ChildSpec s = shell("echo first; echo; echo last >&2; exit 3");
  s.stdout_path = temp("earc-child-out");
  s.stderr_path = temp("earc-child-err");
  ChildOutcome o = runChild(s);
  CHECK(o.started);
  CHECK(o.exit_code == 3);
  CHECK_FALSE(o.signal.has_value());
  CHECK_FALSE(o.killed_at_limit);
  CHECK(o.peak_rss_kb > 0);
  CHECK(firstLine(s.stdout_path) == "first");
  CHECK(lastLine(s.stderr_path) == "last");
  std::filesystem::remove(s.stdout_path);
  std::filesystem::remove(s.stderr_path);
}

TEST_CASE("a hanging child is killed at the wall-clock limit, with its whole process group") {
  ChildOutcome o = runChild(shell("sleep 30 & sleep 30; exit 0", 0.3));
  CHECK(o.killed_at_limit);
  CHECK(o.signal == SIGKILL);
  CHECK(o.wall_s < 5.0);
}

TEST_CASE("test faults make a child crash or hang instead of running its program") {
  ChildSpec crash = shell("exit 0");
  crash.fault = ChildFault::Crash;
  ChildOutcome c = runChild(crash);
  CHECK(c.signal == SIGSEGV);
  ChildSpec hang = shell("exit 0", 0.2);
  hang.fault = ChildFault::Hang;
  CHECK(runChild(hang).killed_at_limit);
}

TEST_CASE("a program that cannot be executed exits 127") {
  ChildSpec s;
  s.argv = {"/nonexistent/program"};
  CHECK(runChild(s).exit_code == 127);
}

TEST_CASE("cancelling kills a running child") {
  std::atomic<bool> cancel{true};
  ChildOutcome o = runChild(shell("sleep 30"), &cancel);
  CHECK(o.cancelled);
  CHECK_FALSE(o.killed_at_limit);
}
