// Damaged database files: the store runs quick_check on open and refuses a
// damaged file before writing to it; a file truncated or with random bytes
// flipped makes every reader throw a StoreError or an InputError (one line
// in the tools, exit 2), never crash or throw anything else.
#include <doctest/doctest.h>

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <thread>

#include "earc/experience/maintenance.hpp"
#include "earc/experience/sampling.hpp"
#include "earc/experience/schema.hpp"
#include "earc/experience/scratch.hpp"
#include "earc/experience/store.hpp"
#include "earc/experience/transfer.hpp"
#include "earc/io/input_error.hpp"

using namespace earc;
using namespace earc::exp;

namespace {

std::vector<unsigned char> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes(static_cast<std::size_t>(std::filesystem::file_size(path)));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  REQUIRE(in.gcount() == static_cast<std::streamsize>(bytes.size()));
  return bytes;
}

void writeBytes(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// A checkpointed database of 2- and 3-disc rows (paths long enough for
// overflow pages), its WAL folded in so the main file is the whole story.
// Each of `doublings` copies every row in SQL: a large file, built cheaply.
void makeDatabase(const std::string& path, std::uint64_t seed, int rows = 30, int doublings = 0) {
  RobotSpec disc;
  disc.radius = 0.3;
  const RobotTraits d = traitsOf(*makeRobotModel(disc, Resolution{}));
  std::mt19937_64 rng(seed);
  std::vector<Experience> batch;
  for (int i = 0; i < rows; ++i)
    batch.push_back(straightLineExperience(std::vector<RobotTraits>(2 + i % 2, d), sampleMobileQuery(2 + i % 2, rng),
                                           40 + i));
  {
    ExperienceStore store(path);
    store.insertAll(batch, -1);
  }
  Connection c(path, OpenMode::ReadWrite);
  for (int i = 0; i < doublings; ++i)
    c.exec(
        "INSERT INTO experiences (kind, robot_count, signature, base_class, key, paths, cost, source, created_at, "
        "solve_time_s, created_session, made_by) SELECT kind, robot_count, signature, base_class, key, paths, cost, "
        "source, created_at, solve_time_s, created_session, made_by FROM experiences ORDER BY id");
  c.exec("PRAGMA wal_checkpoint(TRUNCATE)");
  c.exec("PRAGMA journal_mode = DELETE");
}

std::int64_t pageSize(const std::string& path) {
  Connection c(path, OpenMode::ReadOnly);
  return c.pragmaInt("page_size");
}

std::int64_t rootPage(const std::string& path, const std::string& name) {
  Connection c(path, OpenMode::ReadOnly);
  Statement s = c.prepare("SELECT rootpage FROM sqlite_schema WHERE name = ?1");
  s.bind(1, std::string_view(name));
  REQUIRE(s.step());
  return s.int64At(0);
}

template <class E>
std::string openError(const std::string& path, bool read_only) {
  StoreOptions o;
  o.read_only = read_only;
  try {
    ExperienceStore store(path, o);
  } catch (const E& e) {
    return e.what();
  }
  FAIL("the store opened a damaged file");
  return "";
}

}  // namespace

TEST_CASE("a damaged table page the index scan never reads is caught by quick_check at open") {
  ScratchDirectory dir("hostile");
  const std::string path = dir.file("e.db");
  makeDatabase(path, 1);
  // The table's root page: opening reads only the covering key index, so
  // without quick_check this damage would surface mid-plan, if ever.
  std::vector<unsigned char> bytes = readBytes(path);
  const auto at = static_cast<std::size_t>((rootPage(path, "experiences") - 1) * pageSize(path));
  REQUIRE(at < bytes.size());
  bytes[at] = 0x07;  // not a b-tree page type
  writeBytes(path, bytes);
  for (bool read_only : {true, false}) {
    const std::string msg = openError<DamagedDatabaseError>(path, read_only);
    CHECK(msg.rfind(path + ": damaged database file (", 0) == 0);
    CHECK(msg.find('\n') == std::string::npos);
  }
  // Refused before anything was written: no WAL switch, no session count.
  CHECK(readBytes(path) == bytes);
  CHECK_FALSE(std::filesystem::exists(path + "-wal"));
}

namespace {

// makeDatabase's file in WAL mode, as a planner finds its own database, and
// its bytes with the experiences table's leftmost leaf (rows 1, 2, ...)
// made no b-tree page: damage that quick_check sees, but neither opening
// (which reads the key index) nor an insert (appended on the right) reads.
std::vector<unsigned char> damagedWalDatabase(const std::string& path, int rows = 30, int doublings = 0) {
  makeDatabase(path, 1, rows, doublings);
  {
    Connection c(path, OpenMode::ReadWrite);
    c.exec("PRAGMA journal_mode = WAL");
  }
  std::vector<unsigned char> bytes = readBytes(path);
  const auto page = static_cast<std::size_t>(pageSize(path));
  auto at = static_cast<std::size_t>(rootPage(path, "experiences") - 1) * page;
  REQUIRE(bytes[at] == 0x05);  // an interior page: the table spans several leaves
  while (bytes[at] == 0x05) {  // first cell's left child, down to a leaf
    const std::size_t cell = at + (std::size_t{bytes[at + 12]} << 8 | bytes[at + 13]);
    const std::size_t child = std::size_t{bytes[cell]} << 24 | std::size_t{bytes[cell + 1]} << 16 |
                              std::size_t{bytes[cell + 2]} << 8 | bytes[cell + 3];
    at = (child - 1) * page;
  }
  REQUIRE(bytes[at] == 0x0d);
  bytes[at] = 0x07;
  writeBytes(path, bytes);
  return bytes;
}

StoreOptions backgroundCheck(bool read_only, bool in_open_when_busy = false) {
  StoreOptions o;
  o.check_in_background = true;
  o.check_in_open_when_busy = in_open_when_busy;
  o.read_only = read_only;
  o.new_session = !read_only;
  o.warn_skipped = false;
  return o;
}

Experience oneMore() {
  RobotSpec disc;
  disc.radius = 0.3;
  const RobotTraits d = traitsOf(*makeRobotModel(disc, Resolution{}));
  std::mt19937_64 rng(99);
  return straightLineExperience(std::vector<RobotTraits>(2, d), sampleMobileQuery(2, rng), 30);
}

}  // namespace

TEST_CASE("with quick_check in the background a damaged file opens, but every write throws its error first") {
  ScratchDirectory dir("hostile");
  const std::string path = dir.file("e.db");
  const std::vector<unsigned char> bytes = damagedWalDatabase(path);
  {
    ExperienceStore store(path, backgroundCheck(false));
    CHECK(store.size() == 30);  // the index loaded: the check had not answered
    const Experience e = oneMore();
    auto damaged = [&](auto&& write) {
      try {
        write();
      } catch (const DamagedDatabaseError& err) {
        return std::string(err.what()).rfind(path + ": damaged database file (", 0) == 0;
      }
      return false;
    };
    CHECK(damaged([&] { store.insert(e, -1); }));
    store.recordUse(30, true);  // a row on a sound page
    CHECK(damaged([&] { store.flush(); }));
    CHECK(damaged([&] { (void)store.session(); }));  // the session is never counted
    CHECK(damaged([&] { store.awaitCheck(); }));
    CHECK_NOTHROW(store.close());  // reported already: closing says nothing more
  }
  CHECK(readBytes(path) == bytes);
  // Read-only (earc-plan --no-learn): the verdict comes from awaitCheck, or
  // from close when nobody asked.
  {
    ExperienceStore store(path, backgroundCheck(true));
    CHECK_THROWS_AS(store.awaitCheck(), DamagedDatabaseError);
  }
  {
    ExperienceStore store(path, backgroundCheck(true));
    CHECK_THROWS_AS(store.close(), DamagedDatabaseError);
  }
  CHECK(readBytes(path) == bytes);
}

TEST_CASE("with quick_check in the background a sound file counts its session once, after the check") {
  ScratchDirectory dir("hostile");
  const std::string path = dir.file("e.db");
  makeDatabase(path, 3);
  auto sessions = [&] {
    Connection c(path, OpenMode::ReadOnly);
    Statement s = c.prepare("SELECT value FROM store_meta WHERE name = 'sessions'");
    REQUIRE(s.step());
    return s.int64At(0);
  };
  const std::int64_t before = sessions();
  {
    ExperienceStore store(path, backgroundCheck(false));  // journal_mode DELETE: checked at open
    CHECK(store.checkRun() == ExperienceStore::CheckRun::InOpen);
    CHECK(store.session() == before + 1);
  }
  CHECK(sessions() == before + 1);
  {
    ExperienceStore store(path, backgroundCheck(false));  // now WAL: checked in the background
    CHECK(sessions() == before + 1);  // not yet: the check has not answered
    auto id = store.insert(oneMore(), -1);
    REQUIRE(id.has_value());
    CHECK(store.get(*id)->created_session == before + 2);
    CHECK(store.session() == before + 2);
    // Taken over by the insert where other tests keep the cores busy.
    CHECK(store.checkRun() != ExperienceStore::CheckRun::InOpen);
    store.recordUse(*id, true);
  }
  CHECK(sessions() == before + 2);
  {
    ExperienceStore store(path, backgroundCheck(true));
    CHECK(store.get(31)->succeeded == 1);
    store.awaitCheck();
  }
  CHECK(sessions() == before + 2);
}

TEST_CASE("quick_check runs unmapped with a small cache and gives the connection its settings back") {
  ScratchDirectory dir("hostile");
  const std::string path = dir.file("e.db");
  makeDatabase(path, 2);
  for (OpenMode mode : {OpenMode::ReadOnly, OpenMode::ReadWrite}) {
    Connection c(path, mode);
    const std::int64_t mmap = c.pragmaInt("mmap_size"), cache = c.pragmaInt("cache_size");
    CHECK(mmap == kMmapBytes);
    CHECK(cache == -kPageCacheKiB);
    c.requireQuickCheck();
    CHECK(c.pragmaInt("mmap_size") == mmap);
    CHECK(c.pragmaInt("cache_size") == cache);
  }
  // A damaged file: the error still leaves the settings as they were.
  std::vector<unsigned char> bytes = readBytes(path);
  bytes[static_cast<std::size_t>((rootPage(path, "experiences") - 1) * pageSize(path))] = 0x07;
  writeBytes(path, bytes);
  Connection c(path, OpenMode::ReadOnly);
  CHECK_THROWS_AS(c.requireQuickCheck(), DamagedDatabaseError);
  CHECK(c.pragmaInt("mmap_size") == kMmapBytes);
  CHECK(c.pragmaInt("cache_size") == -kPageCacheKiB);
}

namespace {

// Flips one bit of row `id`'s key where the covering index experiences_keys
// holds it (an index leaf page), not where the table does: the index entry
// no longer matches its row while every page stays well formed, the damage
// a hostile-input probe made with single flipped bytes. Returns the bytes
// written.
std::vector<unsigned char> staleIndexEntry(const std::string& path, std::int64_t id) {
  std::vector<unsigned char> key;
  {
    Connection c(path, OpenMode::ReadOnly);
    Statement s = c.prepare("SELECT key FROM experiences WHERE id = ?1");
    s.bind(1, id);
    REQUIRE(s.step());
    const auto blob = s.blobAt(0);
    key.assign(blob.begin(), blob.end());
  }
  REQUIRE_FALSE(key.empty());
  std::vector<unsigned char> bytes = readBytes(path);
  const auto page = static_cast<std::size_t>(pageSize(path));
  for (auto it = bytes.begin(); (it = std::search(it, bytes.end(), key.begin(), key.end())) != bytes.end(); ++it) {
    const auto at = static_cast<std::size_t>(it - bytes.begin());
    if (bytes[at / page * page] != 0x0a) continue;  // not an index leaf page
    bytes[at + key.size() - 1] ^= 0x01;  // the last double's exponent: a finite key still
    writeBytes(path, bytes);
    return bytes;
  }
  FAIL("row " << id << "'s key is in no index leaf page");
  return bytes;
}

}  // namespace

TEST_CASE("an index entry that no longer matches its row passes quick_check; build, import and curate refuse it") {
  ScratchDirectory dir("hostile");
  const std::string path = dir.file("e.db");
  makeDatabase(path, 5);
  const std::vector<unsigned char> bytes = staleIndexEntry(path, 3);
  const std::string expected = path + ": damaged database file (integrity_check: row 3 missing from index experiences_keys";
  {
    Connection c(path, OpenMode::ReadOnly);
    CHECK_NOTHROW(c.requireQuickCheck());  // what a planner's open runs
    CHECK_THROWS_WITH_AS(c.requireIntegrityCheck(), doctest::Contains(expected.c_str()), DamagedDatabaseError);
  }
  // The store of earc-db build and import (full_check), refused before
  // anything is written: no WAL switch, no migration, no history line.
  StoreOptions writer;
  writer.new_session = false;
  writer.full_check = true;
  try {
    ExperienceStore store(path, writer);
    FAIL("a full check passed a stale index entry");
  } catch (const DamagedDatabaseError& e) {
    const std::string msg = e.what();
    CHECK(msg.rfind(expected, 0) == 0);
    CHECK(msg.find('\n') == std::string::npos);
  }
  // curate in place, and curate -o, which would copy the index as it is.
  CHECK_THROWS_WITH_AS(curateDatabase(path, {}), doctest::Contains(expected.c_str()), DamagedDatabaseError);
  CurateSettings copy;
  copy.output = dir.file("copy.db");
  CHECK_THROWS_WITH_AS(curateDatabase(path, copy), doctest::Contains(expected.c_str()), DamagedDatabaseError);
  CHECK_FALSE(std::filesystem::exists(copy.output));
  CHECK(readBytes(path) == bytes);
  CHECK_FALSE(std::filesystem::exists(path + "-wal"));
}

TEST_CASE("a header file format byte SQLite never writes is refused at every open, naming the byte and its value") {
  ScratchDirectory dir("hostile");
  const std::string path = dir.file("e.db");
  makeDatabase(path, 6);
  {
    Connection c(path, OpenMode::ReadWrite);
    c.exec("PRAGMA journal_mode = WAL");  // as earc keeps its files: 2 in bytes 18 and 19
  }
  const std::vector<unsigned char> sound = readBytes(path);
  REQUIRE(sound[18] == 2);
  REQUIRE(sound[19] == 2);
  // 233 in the write version made SQLite open the file read-only and fail
  // only at the first write, after a plan's or a build's work.
  for (const auto& [at, value] : {std::pair<std::size_t, int>{18, 233}, std::pair<std::size_t, int>{19, 3}}) {
    CAPTURE(at);
    std::vector<unsigned char> bytes = sound;
    bytes[at] = static_cast<unsigned char>(value);
    writeBytes(path, bytes);
    const std::string expected = path + ": damaged database file (SQLite header byte " + std::to_string(at) +
                                 ", the file format " + (at == 18 ? "write" : "read") + " version, is " +
                                 std::to_string(value) + "; SQLite writes 1 or 2 there, earc 2); restore a copy or rebuild it";
    for (OpenMode mode : {OpenMode::ReadOnly, OpenMode::ReadWrite, OpenMode::Hostile})
      CHECK_THROWS_WITH_AS([&] { Connection c(path, mode); }(), expected.c_str(), DamagedDatabaseError);
    for (bool read_only : {true, false}) CHECK(openError<DamagedDatabaseError>(path, read_only) == expected);
    CHECK_THROWS_WITH_AS(verifyDatabase(path), doctest::Contains("SQLite header byte"), InputError);
    CHECK_THROWS_WITH_AS(readImportSource(path), doctest::Contains("SQLite header byte"), InputError);
    CHECK(readBytes(path) == bytes);
  }
}

TEST_CASE("a truncated database is refused as damaged by the store, verify and import, and left as it was") {
  ScratchDirectory dir("hostile");
  const std::string good = dir.file("good.db");
  makeDatabase(good, 2);
  const std::vector<unsigned char> whole = readBytes(good);
  const std::string path = dir.file("cut.db");
  const std::vector<unsigned char> half(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(whole.size() / 2));
  writeBytes(path, half);
  for (bool read_only : {true, false}) {
    const std::string msg = openError<DamagedDatabaseError>(path, read_only);
    CHECK(msg.find(path + ": damaged database file") == 0);
  }
  CHECK(readBytes(path) == half);
  // verify lists the damage (exit 1) or refuses the file (exit 2), naming it.
  try {
    VerifyReport r = verifyDatabase(path);
    CHECK_FALSE(r.ok());
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find(path) == 0);
  }
  CHECK_THROWS_WITH_AS(readImportSource(path), doctest::Contains("damaged database file"), InputError);
}

TEST_CASE("a database missing one of its tables is refused as damaged before anything is written") {
  ScratchDirectory dir("hostile");
  for (const char* table : {"experiences", "store_meta"}) {
    const std::string path = dir.file(std::string("no-") + table + ".db");
    makeDatabase(path, 3);
    {
      Connection c(path, OpenMode::ReadWrite);
      c.exec(std::string("DROP TABLE ") + table);
    }
    const std::vector<unsigned char> before = readBytes(path);
    for (bool read_only : {true, false}) {
      const std::string msg = openError<DamagedDatabaseError>(path, read_only);
      CHECK(msg == path + ": damaged database file (table " + table + " is missing; schema version " +
                       std::to_string(currentSchemaVersion()) + " has it)");
    }
    CHECK(readBytes(path) == before);  // no session counted, nothing migrated
    // verify refuses the file as a whole (earc-db verify: exit 2).
    const std::string missing = std::string("table ") + table + " is missing";
    CHECK_THROWS_WITH_AS(verifyDatabase(path), doctest::Contains(missing.c_str()), InputError);
  }
}

TEST_CASE("a torn WAL keeps the whole transactions before the tear and loses nothing else") {
  ScratchDirectory dir("hostile");
  const std::string path = dir.file("w.db");
  makeDatabase(path, 3, 10);
  const std::string copy = dir.file("copy.db");
  RobotSpec disc;
  disc.radius = 0.3;
  const RobotTraits d = traitsOf(*makeRobotModel(disc, Resolution{}));
  std::mt19937_64 rng(33);
  {
    ExperienceStore store(path);
    store.connection().exec("PRAGMA wal_autocheckpoint = 0");
    for (int i = 0; i < 6; ++i)
      store.insert(straightLineExperience(std::vector<RobotTraits>{d, d}, sampleMobileQuery(2, rng), 40), -1);
    // Copy while the store is open: its close would checkpoint the WAL.
    std::filesystem::copy_file(path, copy);
    std::vector<unsigned char> wal = readBytes(path + "-wal");
    REQUIRE(wal.size() > 5000);
    wal.erase(wal.end() - 3000, wal.end());  // the last commit's frames torn
    writeBytes(copy + "-wal", wal);
  }
  StoreOptions ro;
  ro.read_only = true;
  ExperienceStore store(copy, ro);
  CHECK(store.size() >= 10);
  CHECK(store.size() < 16);
  CHECK(verifyDatabase(copy).ok());
}

TEST_CASE("random bytes flipped in a database make readers throw store or input errors, never crash") {
  ScratchDirectory dir("hostile");
  const std::string good = dir.file("good.db");
  makeDatabase(good, 4, 24);
  const std::vector<unsigned char> original = readBytes(good);
  std::mt19937_64 rng(20240611);
  int refused = 0, opened = 0;
  for (int round = 0; round < 120; ++round) {
    std::vector<unsigned char> bytes = original;
    const int flips = 1 + static_cast<int>(rng() % 6);
    for (int f = 0; f < flips; ++f) {
      const std::size_t at = 100 + rng() % (bytes.size() - 100);  // past the file header
      bytes[at] ^= static_cast<unsigned char>(1u << (rng() % 8));
    }
    const std::string path = dir.file("f" + std::to_string(round) + ".db");
    writeBytes(path, bytes);
    CAPTURE(round);
    try {
      StoreOptions ro;
      ro.read_only = true;
      ExperienceStore store(path, ro);
      ++opened;
      for (const auto& info : store.classes()) {
        std::vector<double> key(info.key_dim, 0.5);
        for (const Match& m : store.nearest(info.cls, key, 5)) CHECK_FALSE(findProblem(m.experience));
      }
    } catch (const StoreError&) {
      ++refused;
    }
    try {
      (void)verifyDatabase(path);
    } catch (const InputError&) {
    }
    try {
      for (const Experience& e : readImportSource(path)) CHECK_FALSE(findProblem(e));
    } catch (const InputError&) {
    }
    std::filesystem::remove(path);
  }
  // Both outcomes occur: the loop exercises refusal and survival alike.
  CHECK(refused > 0);
  CHECK(opened > 0);
}

TEST_CASE("on a machine with no spare core a planner's open checks the file itself or takes over a starved check") {
  // Busy threads on every core this process may use, as other processes
  // would be: the background check's idle-class thread gets no time (a
  // plan of 0.03 s waited 8 to 25 s for its verdict). So it runs in the
  // open, at the planner's priority; and a check left in the background
  // (check_in_open_when_busy off) that starves is stopped and run by the
  // thread that waits for it. Asserted by where the check ran, not by a
  // time: an ASan build beside another test once took 2.35 s, against a
  // bound of 2.16 s, for what took it 0.03 s with the cores free.
  // This thread, and so the threads it starts (the busy ones, the
  // store's check), keep to one core: with busy loops on every core of
  // the process, the idle-class thread still got time now and then where
  // the scheduler left a core idle (CI once saw the check finish in the
  // background in 0.14 s); two loops on its only core leave it none.
  // The file is large (16,000 rows, 45 MB), so that the check needs several
  // of the rare slices the idle class gets: one alone, early in the wait,
  // could end a short check before any wait found it starved.
  ScratchDirectory dir("hostile");
  const std::string path = dir.file("busy.db");
  damagedWalDatabase(path, 250, 6);
  cpu_set_t cpus, one;
  REQUIRE(sched_getaffinity(0, sizeof cpus, &cpus) == 0);
  CPU_ZERO(&one);
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &cpus)) {
      CPU_SET(c, &one);
      break;
    }
  using CheckRun = ExperienceStore::CheckRun;
  for (bool in_open : {true, false}) {
    CAPTURE(in_open);
    REQUIRE(sched_setaffinity(0, sizeof one, &one) == 0);
    std::atomic<bool> stop{false};
    std::atomic<int> spinning{0};
    std::vector<std::thread> busy;
    for (int i = 0; i < 2; ++i)
      busy.emplace_back([&] {
        ++spinning;
        while (!stop.load(std::memory_order_relaxed)) {
        }
      });
    while (spinning.load() < 2) std::this_thread::yield();
    const auto start = std::chrono::steady_clock::now();
    std::string error;
    std::optional<CheckRun> run;  // none: the constructor threw, having checked in the open
    try {
      ExperienceStore store(path, backgroundCheck(true, in_open));
      try {
        store.awaitCheck();
      } catch (const DamagedDatabaseError& e) {
        error = e.what();
      }
      run = store.checkRun();
    } catch (const DamagedDatabaseError& e) {
      error = e.what();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stop = true;
    for (auto& t : busy) t.join();
    REQUIRE(sched_setaffinity(0, sizeof cpus, &cpus) == 0);
    CAPTURE(seconds);
    CHECK(error.rfind(path + ": damaged database file (", 0) == 0);
    if (in_open)
      CHECK_FALSE(run.has_value());
    else
      CHECK(run == CheckRun::TakenOver);
  }
}
