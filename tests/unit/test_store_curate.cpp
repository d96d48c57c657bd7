// Curate: merging, dropping and compacting experience files without
// losing or letting in anything bad.
#include <doctest/doctest.h>

#include "store_transfer_fixtures.hpp"

using namespace earc;
using namespace earc::exp;
using namespace earc::store_test;

TEST_CASE("curate removes near-duplicates keeping the most successful entry") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db");
  std::int64_t first = 0, second = 0;
  {
    RobotSpec disc;
    disc.radius = 0.3;
    const RobotTraits d = traitsOf(*makeRobotModel(disc, Resolution{}));
    std::mt19937_64 rng(8);
    ExperienceStore store(a);
    Experience e = straightLineExperience(std::vector<RobotTraits>{d, d}, sampleMobileQuery(2, rng), 5);
    first = *store.insert(e, -1);
    second = *store.insert(e, -1);
    store.insert(straightLineExperience(std::vector<RobotTraits>{d, d}, sampleMobileQuery(2, rng), 5), -1);
    store.recordUse(second, true);
  }
  CurateSettings s;
  s.dedupe_eps = 1e-9;
  CurateReport r = curateDatabase(a, s);
  CHECK(r.duplicates_removed == 1);
  CHECK(r.rows_after == 2);
  StoreOptions ro;
  ro.read_only = true;
  ExperienceStore store(a, ro);
  CHECK_FALSE(store.get(first).has_value());
  CHECK(store.get(second).has_value());
}

TEST_CASE("curate drops entries never retrieved, optionally only old ones") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db");
  fill(a, 9);  // session 1: 60 rows, 15 of them retrieved
  {
    ExperienceStore later(a);  // sessions 2 and 3
  }
  {
    ExperienceStore later(a);
  }
  CurateSettings keep_recent;
  keep_recent.drop_unused = true;
  keep_recent.older_than_sessions = 3;  // created in session <= 0: none
  CHECK(curateDatabase(a, keep_recent).unused_removed == 0);
  CurateSettings old;
  old.drop_unused = true;
  old.older_than_sessions = 2;  // created in session <= 1
  CurateReport r = curateDatabase(a, old);
  CHECK(r.unused_removed == 45);
  CHECK(r.rows_after == 15);
}

TEST_CASE("curate drops the entries of the builds named, and those of no known build for \"\"") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db");
  fill(a, 12);  // 60 rows: 20 arm rows, 10 by 0.0.9+abc1234, 10 not known; 40 by this build
  CurateSettings older;
  older.drop_made_by = {"0.0.9+abc1234", "0.0.1+none"};
  CurateReport r = curateDatabase(a, older);
  CHECK(r.made_by_removed == 10);
  CHECK(r.rows_after == 50);
  InspectReport seen = inspectDatabase(a, 0);
  REQUIRE(seen.builds.size() == 2);
  CHECK(seen.builds[0] == std::pair<std::string, std::int64_t>{std::string(version()), 40});
  CHECK(seen.builds[1] == std::pair<std::string, std::int64_t>{"", 10});
  CurateSettings unknown;
  unknown.drop_made_by = {""};
  CHECK(curateDatabase(a, unknown).made_by_removed == 10);
  CHECK(rowCount(a) == 40);
}

TEST_CASE("curate --drop-made-by takes patterns: every dirty build's rows, and no more") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db");
  fill(a, 13);  // 10 by 0.0.9+abc1234, 10 not known, 40 by this build (renamed 0.2.0+1234567)
  {
    Connection c(a, OpenMode::ReadWrite);
    // This build's name may end in .dirty itself (a tree with changes).
    c.exec("UPDATE experiences SET made_by = '0.2.0+1234567' WHERE made_by NOT IN ('', '0.0.9+abc1234')");
    c.exec("UPDATE experiences SET made_by = '0.0.9+abc1234.dirty' WHERE id IN "
           "(SELECT id FROM experiences WHERE made_by = '0.0.9+abc1234' LIMIT 4)");
    c.exec("UPDATE experiences SET made_by = '0.1.0+def5678.dirty' WHERE id IN "
           "(SELECT id FROM experiences WHERE made_by = '' LIMIT 3)");
  }
  CurateSettings dirty;
  dirty.drop_made_by = {"*.dirty"};
  CHECK(curateDatabase(a, dirty).made_by_removed == 7);
  CurateSettings exact;  // a name without wildcards is matched exactly, not as a prefix
  exact.drop_made_by = {"0.0.9+abc"};
  CHECK(curateDatabase(a, exact).made_by_removed == 0);
  CurateSettings one;
  one.drop_made_by = {"0.0.?+abc1234"};
  CHECK(curateDatabase(a, one).made_by_removed == 6);
  CHECK(rowCount(a) == 47);  // 0.2.0's 40 and 7 not known
}

TEST_CASE("curate --drop-unused judges this file's own rows: merged rows stay, a never-used file is refused") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db"), b = dir.file("b.db"), fresh = dir.file("fresh.db");
  fill(a, 14);  // 60 rows, 15 of them retrieved
  fill(b, 15);  // 60 others, never retrieved in a
  CurateSettings s;
  s.drop_unused = true;
  s.merge = {b};
  CurateReport r = curateDatabase(a, s);
  CHECK(r.unused_removed == 45);
  CHECK(r.merged == 60);
  CHECK(rowCount(a) == 75);
  // A file no plan has used: every row is "unused"; refused, unchanged.
  {
    ExperienceStore store(fresh);
    std::mt19937_64 rng(3);
    RobotSpec disc;
    disc.radius = 0.3;
    const RobotTraits d = traitsOf(*makeRobotModel(disc, Resolution{}));
    for (int i = 0; i < 5; ++i)
      store.insert(straightLineExperience(std::vector<RobotTraits>{d, d}, sampleMobileQuery(2, rng), 5), -1);
  }
  CurateSettings drop;
  drop.drop_unused = true;
  drop.dedupe_eps = 1e-9;
  try {
    curateDatabase(fresh, drop);
    FAIL("--drop-unused emptied a file no plan has used");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CHECK(what.find(fresh) != std::string::npos);
    CHECK(what.find("--drop-unused: no entry has been retrieved yet") != std::string::npos);
  }
  CHECK(rowCount(fresh) == 5);
  // Sparing the rows of the last session, it would not empty the file.
  drop.older_than_sessions = 1;
  CHECK(curateDatabase(fresh, drop).unused_removed == 0);
  CHECK(rowCount(fresh) == 5);
}

TEST_CASE("curate into a copy merges other files and leaves the original untouched") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db"), b = dir.file("b.db"), out = dir.file("merged.db");
  fill(a, 10);
  fill(b, 11);
  CurateSettings s;
  s.merge = {b, b};  // the same file twice: its rows once
  s.output = out;
  CurateReport r = curateDatabase(a, s);
  CHECK(r.merged == 60);
  CHECK(rowCount(out) == 120);
  CHECK(rowCount(a) == 60);
  CHECK(verifyDatabase(out).ok());
  CHECK_THROWS_AS(copyDatabase(a, out), InputError);  // never overwrites
}

TEST_CASE("a curated copy appears only when complete: a failure leaves no file under its name") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db"), bad = dir.file("bad.jsonl"), out = dir.file("copy.db");
  fill(a, 10);
  {
    std::ofstream f(bad);
    f << "not an export\n";
  }
  CurateSettings s;
  s.merge = {bad};  // fails after the copy was made
  s.output = out;
  CHECK_THROWS_AS(curateDatabase(a, s), InputError);
  // Nothing under the copy's name, and no temporary left beside it.
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    CHECK_MESSAGE(e.path().filename().string().rfind("copy.db", 0) != 0, e.path());
  CHECK(rowCount(a) == 60);
  // The same curation without the bad file then succeeds.
  s.merge.clear();
  CHECK(curateDatabase(a, s).rows_after == 60);
  CHECK(rowCount(out) == 60);
  CHECK(verifyDatabase(out).ok());
}

namespace {

// Rewrites the path blob of every row matching `where` in format version 1,
// as an earc before version 2 wrote it. Returns how many.
int toVersion1(const std::string& path, const std::string& where) {
  Connection c(path, OpenMode::ReadWrite);
  std::vector<std::pair<std::int64_t, std::vector<unsigned char>>> old;
  Statement get = c.prepare("SELECT id, paths FROM experiences WHERE " + where);
  while (get.step()) old.emplace_back(get.int64At(0), encodePathsV1(decodePaths(get.blobAt(1), get.int64At(0))));
  Statement put = c.prepare("UPDATE experiences SET paths = ?1 WHERE id = ?2");
  for (auto& [id, blob] : old) {
    put.bindBlob(1, blob).bind(2, id);
    put.run();
    put.reset();
  }
  return static_cast<int>(old.size());
}

std::vector<unsigned char> pathBlob(const std::string& path, std::int64_t id) {
  Connection c(path, OpenMode::ReadOnly);
  Statement get = c.prepare("SELECT paths FROM experiences WHERE id = ?1");
  get.bind(1, id);
  REQUIRE(get.step());
  return std::vector<unsigned char>(get.blobAt(0).begin(), get.blobAt(0).end());
}

}  // namespace

TEST_CASE("curate --compact rewrites older path blobs into the same rows, and the file shrinks") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db");
  fill(a, 12, 100);
  const int older = toVersion1(a, "id % 3 <> 0");
  REQUIRE(older == 200);
  CHECK(inspectDatabase(a, 0).older_path_blobs == 200);
  const auto before = contents(a);
  CurateSettings s;
  s.vacuum = true;
  curateDatabase(a, s);  // the same file size to compare with, less what vacuum alone gives back
  const std::int64_t size_before = inspectDatabase(a, 0).file_bytes;
  s.vacuum = false;
  s.compact = true;
  CurateReport r = curateDatabase(a, s);
  CHECK(r.blobs_rewritten == 200);
  CHECK(r.rows_after == 300);
  CHECK(r.damaged_rows == 0);
  const InspectReport after = inspectDatabase(a, 0);
  CHECK(after.older_path_blobs == 0);
  CHECK(after.file_bytes < size_before);
  CHECK(contents(a) == before);  // every double, counter and time as it was
  CHECK(verifyDatabase(a).ok());
  CHECK(curateDatabase(a, s).blobs_rewritten == 0);
}

TEST_CASE("curate --compact leaves a damaged older blob as it was, and says so") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db");
  fill(a, 13, 4);
  REQUIRE(toVersion1(a, "1") == 12);
  {
    Connection c(a, OpenMode::ReadWrite);
    c.exec("UPDATE experiences SET paths = substr(paths, 1, 40) WHERE id = 5");
  }
  const auto damaged = pathBlob(a, 5);
  CurateSettings s;
  s.compact = true;
  CurateReport r = curateDatabase(a, s);
  CHECK(r.blobs_rewritten == 11);
  CHECK(r.damaged_rows == 1);
  CHECK(pathBlob(a, 5) == damaged);
  CHECK(inspectDatabase(a, 0).older_path_blobs == 1);
  CHECK(readPathBlobHeader(pathBlob(a, 6), 6).version == kPathBlobVersion);
}

TEST_CASE("inspect counts only version 1 path blobs as older, not damaged ones or a newer earc's") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db");
  fill(a, 14, 4);
  {
    Connection c(a, OpenMode::ReadWrite);
    c.exec("UPDATE experiences SET paths = substr(paths, 1, 4) || x'0300' || substr(paths, 7) WHERE id = 3");
    c.exec("UPDATE experiences SET paths = x'00' WHERE id = 4");
  }
  CHECK(inspectDatabase(a, 0).older_path_blobs == 0);
  REQUIRE(toVersion1(a, "id = 6") == 1);
  CHECK(inspectDatabase(a, 0).older_path_blobs == 1);
  CurateSettings s;
  s.compact = true;
  CurateReport r = curateDatabase(a, s);
  CHECK(r.blobs_rewritten == 1);
  CHECK(r.damaged_rows == 2);
}
