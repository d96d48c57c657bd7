// The experience store's contract: retrieval, near-duplicate checks, usage
// counters, sharing one file between connections, and corrupt rows.
#include <doctest/doctest.h>

#include <filesystem>
#include <random>

#include "earc/experience/maintenance.hpp"
#include "earc/experience/path_blob.hpp"
#include "earc/experience/sampling.hpp"
#include "earc/experience/scratch.hpp"
#include "earc/experience/store.hpp"
#include "earc/util/version.hpp"
#include "support.hpp"

using earc::test::discTraits;
using earc::test::readOnly;

using namespace earc;
using namespace earc::exp;

namespace {

Experience sample(std::mt19937_64& rng, int robots = 2, double radius = 0.3) {
  const std::vector<RobotTraits> traits(static_cast<std::size_t>(robots), discTraits(radius));
  return straightLineExperience(traits, sampleMobileQuery(robots, rng), 8);
}

}  // namespace

TEST_CASE("an inserted experience is retrieved decoded and unchanged") {
  ScratchDirectory dir("store");
  std::mt19937_64 rng(1);
  ExperienceStore store(dir.file("e.db"));
  Experience e = sample(rng);
  e.solve_time_s = 0.25;
  auto id = store.insert(e, -1);
  REQUIRE(id.has_value());
  auto found = store.nearest(e.cls, e.key, 5);
  REQUIRE(found.size() == 1);
  const Experience& got = found.front().experience;
  CHECK(got.id == *id);
  CHECK(got.cls == e.cls);
  CHECK(got.key == e.key);
  CHECK(got.paths == e.paths);
  CHECK(got.cost == e.cost);
  CHECK(got.solve_time_s == 0.25);
  CHECK(got.source == Source::Build);
  CHECK(got.created_at > 0);
  CHECK(got.created_session == store.session());
  CHECK(got.made_by == version());  // made by this build
  CHECK_FALSE(got.made_by.empty());
  CHECK(found.front().distance == 0.0);
}

TEST_CASE("nearest returns the k closest of the class only, nearest first") {
  ScratchDirectory dir("store");
  std::mt19937_64 rng(2);
  ExperienceStore store(dir.file("e.db"));
  std::vector<Experience> batch;
  for (int i = 0; i < 200; ++i) batch.push_back(sample(rng));
  for (int i = 0; i < 50; ++i) batch.push_back(sample(rng, 2, 0.5));  // other class
  store.insertAll(batch, -1);
  const Experience& probe = batch[17];
  auto found = store.nearest(probe.cls, probe.key, 10);
  REQUIRE(found.size() == 10);
  CHECK(found.front().experience.key == probe.key);
  for (std::size_t i = 1; i < found.size(); ++i) {
    CHECK(found[i - 1].distance <= found[i].distance);
    CHECK(found[i].experience.cls == probe.cls);
  }
  CHECK(store.classes().size() == 2);

  // The next ones after the first 4, without those 4.
  auto next = store.nearest(probe.cls, probe.key, 10, 4);
  REQUIRE(next.size() == 6);
  for (std::size_t i = 0; i < next.size(); ++i) CHECK(next[i].experience.id == found[i + 4].experience.id);
  CHECK(store.nearest(probe.cls, probe.key, 10, 10).empty());
  CHECK(store.nearest(probe.cls, probe.key, 3, 10).empty());
}

TEST_CASE("a near-duplicate is not inserted twice") {
  ScratchDirectory dir("store");
  std::mt19937_64 rng(3);
  ExperienceStore store(dir.file("e.db"));
  Experience e = sample(rng);
  CHECK(store.insert(e, 1e-3).has_value());
  CHECK_FALSE(store.insert(e, 1e-3).has_value());
  Experience shifted = e;
  for (Path& p : shifted.paths) p.raw()[0] += 0.5;  // first start x moves by 0.5
  shifted.key = keyOfCanonicalPaths(shifted.cls.kind, shifted.paths);
  CHECK(store.insert(shifted, 0.1).has_value());
  CHECK(store.insert(e, -1).has_value());  // eps < 0: no check
  CHECK(store.size() == 3);
}

TEST_CASE("a batch insert skips near-duplicates within the batch itself") {
  ScratchDirectory dir("store");
  std::mt19937_64 rng(4);
  ExperienceStore store(dir.file("e.db"));
  Experience a = sample(rng), b = sample(rng);
  auto ids = store.insertAll({a, b, a}, 1e-6);
  REQUIRE(ids.size() == 3);
  CHECK(ids[0].has_value());
  CHECK(ids[1].has_value());
  CHECK_FALSE(ids[2].has_value());
}

TEST_CASE("an inconsistent experience is refused at insert") {
  ScratchDirectory dir("store");
  std::mt19937_64 rng(5);
  ExperienceStore store(dir.file("e.db"));
  Experience e = sample(rng);
  e.key[0] += 1.0;  // no longer the paths' start
  CHECK_THROWS_WITH_AS(store.insert(e, -1), doctest::Contains("key value 0"), std::invalid_argument);
  Experience f = sample(rng);
  f.cls.robot_count = 3;
  CHECK_THROWS_AS(store.insert(f, -1), std::invalid_argument);
  CHECK(store.size() == 0);
}

TEST_CASE("usage counters are buffered and written by flush and at close") {
  ScratchDirectory dir("store");
  std::mt19937_64 rng(6);
  const std::string path = dir.file("e.db");
  std::int64_t id = 0;
  {
    ExperienceStore store(path);
    id = *store.insert(sample(rng), -1);
    store.recordUse(id, true);
    store.recordUse(id, false);
    {
      ExperienceStore other(path, readOnly());
      CHECK(other.get(id)->retrieved == 0);  // still buffered
    }
    store.flush();
    CHECK(store.get(id)->retrieved == 2);
    CHECK(store.get(id)->succeeded == 1);
    store.recordUse(id, true);
  }
  ExperienceStore reopened(path, readOnly());
  CHECK(reopened.get(id)->retrieved == 3);
  CHECK(reopened.get(id)->succeeded == 2);
}

TEST_CASE("usage counters stop at kMaxUseCount instead of overflowing; rows past it are refused") {
  // An imported file may carry counters near the 64-bit limit: SQLite's
  // sum past it turned the column into a real number, and every reader
  // then refused the file. inspect's sums over a class overflowed too.
  ScratchDirectory dir("store");
  std::mt19937_64 rng(16);
  const std::string path = dir.file("e.db");
  std::vector<std::int64_t> ids;
  {
    ExperienceStore store(path);
    for (int i = 0; i < 3; ++i) {
      Experience e = sample(rng);
      e.retrieved = kMaxUseCount - 1;
      e.succeeded = kMaxUseCount - 2;
      ids.push_back(*store.insert(e, -1));
    }
    for (int use = 0; use < 3; ++use)
      for (std::int64_t id : ids) store.recordUse(id, true);
    store.flush();
    for (std::int64_t id : ids) {
      CHECK(store.get(id)->retrieved == kMaxUseCount);
      CHECK(store.get(id)->succeeded == kMaxUseCount);
    }
    Experience over = sample(rng);
    over.retrieved = over.succeeded = kMaxUseCount + 1;
    CHECK_THROWS_WITH_AS(store.insert(over, -1), doctest::Contains("usage counters out of range"),
                         std::invalid_argument);
    Experience late = sample(rng);
    late.created_at = kMaxCreatedAt + 1;
    CHECK_THROWS_WITH_AS(store.insert(late, -1), doctest::Contains("after the year 9999"), std::invalid_argument);
  }
  CHECK(verifyDatabase(path).ok());
  const InspectReport r = inspectDatabase(path, 3);
  REQUIRE(r.classes.size() == 1);
  CHECK(r.classes[0].retrieved == 3 * kMaxUseCount);
  CHECK(r.classes[0].succeeded == 3 * kMaxUseCount);
}

TEST_CASE("a store sees rows another connection inserted since it opened") {
  ScratchDirectory dir("store");
  std::mt19937_64 rng(7);
  const std::string path = dir.file("e.db");
  ExperienceStore a(path), b(path);
  Experience e = sample(rng);
  REQUIRE(b.insert(e, -1).has_value());
  auto found = a.nearest(e.cls, e.key, 1);
  REQUIRE(found.size() == 1);
  CHECK(found.front().distance == 0.0);
  // ... and a's duplicate check counts b's row.
  CHECK_FALSE(a.insert(e, 1e-9).has_value());
}

TEST_CASE("a store reloads its index after another connection deleted rows") {
  ScratchDirectory dir("store");
  std::mt19937_64 rng(8);
  const std::string path = dir.file("e.db");
  ExperienceStore a(path), b(path);
  Experience e1 = sample(rng), e2 = sample(rng);
  auto id1 = a.insert(e1, -1);
  a.insert(e2, -1);
  b.connection().exec("DELETE FROM experiences WHERE id = " + std::to_string(*id1));
  a.refresh();
  CHECK(a.size() == 1);
  CHECK(a.nearest(e1.cls, e1.key, 5).size() == 1);
}

TEST_CASE("every read-write open counts one session, read-only opens do not") {
  ScratchDirectory dir("store");
  const std::string path = dir.file("e.db");
  { ExperienceStore s(path); }
  { ExperienceStore s(path, readOnly()); }
  StoreOptions quiet;
  quiet.new_session = false;
  { ExperienceStore s(path, quiet); }
  ExperienceStore s(path);
  CHECK(s.session() == 2);
}

TEST_CASE("a store opened read-only refuses to write") {
  ScratchDirectory dir("store");
  std::mt19937_64 rng(9);
  const std::string path = dir.file("e.db");
  { ExperienceStore s(path); }
  ExperienceStore ro(path, readOnly());
  CHECK_THROWS_AS(ro.insert(sample(rng), -1), std::logic_error);
  CHECK_THROWS_AS(ro.recordUse(1, true), std::logic_error);
}

TEST_CASE("a read-only store writes nothing and leaves no -wal or -shm beside the file") {
  ScratchDirectory dir("store");
  std::mt19937_64 rng(10);
  const std::string path = dir.file("e.db");
  auto beside = [&] { return std::filesystem::exists(path + "-wal") || std::filesystem::exists(path + "-shm"); };
  { ExperienceStore s(path); s.insert(sample(rng), -1); }
  REQUIRE_FALSE(beside());
  {
    // It opens the file read-write (so that it may remove those files when
    // it closes last), under query_only: SQL that writes is refused too.
    ExperienceStore ro(path, readOnly());
    CHECK_THROWS_AS(ro.connection().exec("DELETE FROM experiences"), StoreError);
    CHECK(ro.size() == 1);
  }
  CHECK_FALSE(beside());
  {
    // Closing while a writer is open leaves the writer's files to it.
    ExperienceStore writer(path);
    { ExperienceStore ro(path, readOnly()); }
    CHECK(writer.insert(sample(rng), -1).has_value());
    ExperienceStore ro(path, readOnly());
    CHECK(ro.size() == 2);
  }
  CHECK_FALSE(beside());
}

TEST_CASE("a row with a corrupt path blob is skipped by retrieval and named when read") {
  ScratchDirectory dir("store");
  std::mt19937_64 rng(10);
  const std::string path = dir.file("e.db");
  ExperienceStore store(path);
  Experience e = sample(rng);
  auto bad = *store.insert(e, -1);
  Experience near = e;
  for (Path& p : near.paths) p.raw()[1] += 0.01;
  near.key = keyOfCanonicalPaths(near.cls.kind, near.paths);
  store.insert(near, -1);
  store.connection().exec("UPDATE experiences SET paths = X'00010203' WHERE id = " + std::to_string(bad));
  auto found = store.nearest(e.cls, e.key, 5);
  REQUIRE(found.size() == 1);
  CHECK(found.front().experience.id != bad);
  CHECK_THROWS_WITH_AS(store.get(bad), doctest::Contains(("row " + std::to_string(bad)).c_str()), CorruptRowError);
}

TEST_CASE("a store used after close says so instead of crashing") {
  ScratchDirectory dir("store");
  ExperienceStore store(dir.file("e.db"));
  store.close();
  CHECK_THROWS_AS(store.refresh(), std::logic_error);
  store.close();  // idempotent
}
