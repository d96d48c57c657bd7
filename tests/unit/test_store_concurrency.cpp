// Several processes sharing one experience file (shared/design/
// reliability.md, "Many processes at once"): no lost rows, no duplicate
// rows, no unhandled SQLITE_BUSY, integrity intact.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <random>
#include <set>

#include "earc/experience/maintenance.hpp"
#include "earc/experience/sampling.hpp"
#include "earc/experience/schema.hpp"
#include "earc/experience/scratch.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/experience/store.hpp"

using namespace earc;
using namespace earc::exp;

namespace {

constexpr int kRowsPerChild = 300;

// Runs in a forked child: opens its own connection (none is inherited),
// inserts kRowsPerChild distinct rows one transaction each, marking each
// with solve_time_s = child * 1000 + i. Never returns.
[[noreturn]] void insertRows(const std::string& path, int child) {
  int status = 0;
  try {
    RobotSpec spec;
    spec.radius = 0.3;
    const RobotTraits disc = traitsOf(*makeRobotModel(spec, Resolution{}));
    std::vector<RobotTraits> robots{disc, disc};
    std::mt19937_64 rng(static_cast<std::uint64_t>(100 + child));
    ExperienceStore store(path);
    for (int i = 0; i < kRowsPerChild; ++i) {
      Experience e = straightLineExperience(robots, sampleMobileQuery(2, rng), 4);
      e.solve_time_s = child * 1000 + i;
      if (!store.insert(e, 0.0)) status = 1;  // distinct keys: never a duplicate
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "child %d: %s\n", child, e.what());
    status = 2;
  }
  std::fflush(stderr);
  _exit(status);
}

// Whether this process holds a POSIX lock on some byte of `path`, asked
// from a forked child (F_GETLK does not see the asker's own locks).
bool lockHeldOn(const std::string& path) {
  const pid_t child = ::fork();
  if (child == 0) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    struct flock probe {};
    probe.l_type = F_WRLCK;
    probe.l_whence = SEEK_SET;
    const bool locked = fd >= 0 && ::fcntl(fd, F_GETLK, &probe) == 0 && probe.l_type != F_UNLCK;
    _exit(locked ? 0 : 1);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace

// Closing any descriptor of a file drops every POSIX lock the process holds
// on it. A plan's background quick_check opened a second connection, whose
// header read did that: its main connection then held no lock, another
// process closing the file took itself for the last user and deleted the
// WAL under it, and two plans sharing a database damaged it.
TEST_CASE("a second connection to a file in one process leaves the first one's lock in place") {
  ScratchDirectory dir("locks");
  const std::string path = dir.file("e.db");
  ExperienceStore store(path);
  REQUIRE(lockHeldOn(path));  // a WAL connection keeps a shared lock while open
  { Connection other(path, OpenMode::ReadOnly); }
  CHECK(lockHeldOn(path));
  { Connection other(path, OpenMode::Hostile); }
  CHECK(lockHeldOn(path));
  CHECK(startsLikeSqlite(path));
  CHECK(lockHeldOn(path));
  store.awaitCheck();  // the background quick_check's own connection
  CHECK(lockHeldOn(path));
}

TEST_CASE("two processes inserting into one new file at once lose no row and duplicate none") {
  ScratchDirectory dir("concurrency");
  const std::string path = dir.file("shared.db");
  // No connection is open in this process when the children are forked;
  // the children even race to create and migrate the file.
  std::vector<pid_t> children;
  for (int child = 0; child < 2; ++child) {
    pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) insertRows(path, child);
    children.push_back(pid);
  }
  for (pid_t pid : children) {
    int status = 0;
    REQUIRE(waitpid(pid, &status, 0) == pid);
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
  }
  Connection c(path, OpenMode::ReadOnly);
  CHECK(c.pragmaText("integrity_check") == "ok");
  Statement rows = c.prepare("SELECT CAST(solve_time_s AS INTEGER), count(*) FROM experiences GROUP BY 1");
  std::set<std::int64_t> markers;
  std::int64_t max_count = 0;
  while (rows.step()) {
    markers.insert(rows.int64At(0));
    max_count = std::max(max_count, rows.int64At(1));
  }
  CHECK(markers.size() == 2 * kRowsPerChild);
  CHECK(max_count == 1);
  for (int child = 0; child < 2; ++child)
    for (int i = 0; i < kRowsPerChild; ++i) CHECK(markers.count(child * 1000 + i) == 1);
  // One creation (whichever child won the race) and one line per child
  // counting its own rows.
  const HistoryTail history = readHistory(c, currentSchemaVersion(), 10);
  REQUIRE(history.lines.size() == 3);
  CHECK(history.lines[0].operation == "create");
  CHECK(history.lines[1].rows_added == kRowsPerChild);
  CHECK(history.lines[2].rows_added == kRowsPerChild);
  CHECK(c.pragmaInt("user_version") == currentSchemaVersion());
}

namespace {

// Runs in a forked child: inserts rows until killed, writing each marker
// to `fd` only after insert() returned (the commit is reported). Never returns.
[[noreturn]] void insertUntilKilled(const std::string& path, int round, int fd) {
  try {
    RobotSpec spec;
    spec.radius = 0.3;
    const RobotTraits disc = traitsOf(*makeRobotModel(spec, Resolution{}));
    std::vector<RobotTraits> robots{disc, disc};
    std::mt19937_64 rng(static_cast<std::uint64_t>(500 + round));
    ExperienceStore store(path);
    for (std::int64_t i = 0;; ++i) {
      Experience e = straightLineExperience(robots, sampleMobileQuery(2, rng), 4);
      e.solve_time_s = static_cast<double>(round * 100000 + i);
      if (i % 5 == 4) {
        store.insertAll({e, e}, -1);  // a two-row transaction now and then
      } else {
        store.insert(e, -1);
      }
      const std::int64_t marker = round * 100000 + i;
      if (write(fd, &marker, sizeof marker) != sizeof marker) _exit(3);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "crash child: %s\n", e.what());
  }
  _exit(2);
}

}  // namespace

TEST_CASE("a writer killed at random moments loses no reported commit and leaves an intact file") {
  ScratchDirectory dir("crash");
  const std::string path = dir.file("crash.db");
  std::set<std::int64_t> reported;
  std::mt19937_64 rng(42);
  for (int round = 0; round < 5; ++round) {
    int fds[2];
    REQUIRE(pipe(fds) == 0);
    pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      close(fds[0]);
      insertUntilKilled(path, round, fds[1]);
    }
    close(fds[1]);
    usleep(static_cast<useconds_t>(50000 + rng() % 250000));  // 50-300 ms of inserting
    kill(pid, SIGKILL);
    int status = 0;
    REQUIRE(waitpid(pid, &status, 0) == pid);
    CHECK(WIFSIGNALED(status));
    std::int64_t marker = 0;
    while (read(fds[0], &marker, sizeof marker) == sizeof marker) reported.insert(marker);
    close(fds[0]);
  }
  REQUIRE(reported.size() > 5);
  {
    Connection c(path, OpenMode::ReadOnly);
    CHECK(c.pragmaText("integrity_check") == "ok");
    Statement rows = c.prepare("SELECT CAST(solve_time_s AS INTEGER) FROM experiences");
    std::set<std::int64_t> stored;
    while (rows.step()) stored.insert(rows.int64At(0));
    for (std::int64_t m : reported) CHECK_MESSAGE(stored.count(m) == 1, "reported commit " << m << " is missing");
    // Each killed writer's history line counts exactly its committed rows.
    Statement per_round = c.prepare("SELECT CAST(solve_time_s AS INTEGER) / 100000, count(*) FROM experiences GROUP BY 1 ORDER BY 1");
    std::vector<std::int64_t> committed;
    while (per_round.step()) committed.push_back(per_round.int64At(1));
    std::vector<std::int64_t> counted;
    for (const HistoryLine& l : readHistory(c, currentSchemaVersion(), 100).lines)
      if (l.operation == "learn") counted.push_back(l.rows_added);
    CHECK(counted == committed);
  }
  CHECK(verifyDatabase(path).ok());
  ExperienceStore reopened(path);  // and the file is usable for writing again
  CHECK(reopened.size() >= reported.size());
}

TEST_CASE("a read transaction sees one snapshot while another connection commits, and ends on any exit") {
  ScratchDirectory dir("read-snapshot");
  const std::string path = dir.file("r.db");
  Connection writer(path, OpenMode::ReadWrite);
  writer.enableWal();
  writer.exec("CREATE TABLE t (x INTEGER)");
  writer.exec("INSERT INTO t VALUES (1)");
  Connection reader(path, OpenMode::ReadOnly);
  auto count = [&] {
    Statement s = reader.prepare("SELECT count(*) FROM t");
    REQUIRE(s.step());
    return s.int64At(0);
  };
  // Statements of one read() share a snapshot: the writer's commit between
  // them is not seen until the transaction ends.
  const auto [before, during] = reader.read([&] {
    const std::int64_t first = count();
    writer.exec("INSERT INTO t VALUES (2)");
    return std::pair{first, count()};
  });
  CHECK(before == 1);
  CHECK(during == 1);
  CHECK(sqlite3_get_autocommit(reader.handle()) != 0);
  CHECK(count() == 2);
  // An exception ends the transaction too (and is passed on).
  CHECK_THROWS_AS(reader.read([&]() -> int { count(); throw std::runtime_error("x"); }), std::runtime_error);
  CHECK(sqlite3_get_autocommit(reader.handle()) != 0);
  // Inside a write transaction, read() joins it.
  writer.write([&] {
    writer.exec("INSERT INTO t VALUES (3)");
    writer.read([&] { writer.exec("INSERT INTO t VALUES (4)"); });
    CHECK(sqlite3_get_autocommit(writer.handle()) == 0);
  });
  CHECK(count() == 4);
}
