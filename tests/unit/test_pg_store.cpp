// The PostgreSQL experience store against a real server: migrations,
// refusals, retrieval, sharing between connections and processes, and a
// writer killed mid-transaction. Skipped in the plain unit run: they need
// a server, which tests/cli/pg_store.sh starts (tools/postgres-dev.sh) and
// names in EARC_TEST_PG_URI before running them with --no-skip.
#include <doctest/doctest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "earc/experience/maintenance.hpp"
#include "earc/experience/path_blob.hpp"
#include "earc/experience/pg_connection.hpp"
#include "earc/experience/pg_schema.hpp"
#include "earc/experience/sampling.hpp"
#include "earc/experience/scratch.hpp"
#include "earc/experience/store.hpp"
#include "earc/experience/transfer.hpp"
#include "../../src/experience/pg_warm_pack.hpp"
#include "../../src/experience/pg_warm_rows.hpp"
#include "row_cache_checks.hpp"
#include "support.hpp"

using earc::test::discTraits;

using namespace earc;
using namespace earc::exp;

namespace {

std::string pgFileText(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A new, empty database on the test server; its URI.
std::string freshDatabase() {
  const char* admin = std::getenv("EARC_TEST_PG_URI");
  REQUIRE_MESSAGE(admin, "EARC_TEST_PG_URI is not set (tests/cli/pg_store.sh sets it)");
  static std::mt19937_64 rng(std::random_device{}());
  const std::string name = "earc_t" + std::to_string(rng() % 1000000000);
  PgConnection db(admin);
  db.exec("CREATE DATABASE " + name);
  std::string uri = admin;
  return uri.substr(0, uri.rfind('/') + 1) + name;
}

Experience pgSample(std::mt19937_64& rng, int robots = 2) {
  const std::vector<RobotTraits> traits(static_cast<std::size_t>(robots), discTraits(0.3));
  return straightLineExperience(traits, sampleMobileQuery(robots, rng), 8);
}

// `count` rows drawn from rng, row i of 2 + i % kinds robots.
std::vector<Experience> pgSamples(std::mt19937_64& rng, int count, int kinds = 1) {
  std::vector<Experience> rows;
  for (int i = 0; i < count; ++i) rows.push_back(pgSample(rng, 2 + i % kinds));
  return rows;
}

std::int64_t pgRows(const std::string& uri) {
  PgConnection db(uri);
  return db.query("SELECT count(*) FROM earc.experiences").int64At(0, 0);
}

// Runs in a forked child: its own store, `rows` single-row inserts (or
// batches of `batch`), each row marked solve_time_s = child * 100000 + i;
// writes the ids it was given to `ids_file`. Never returns.
[[noreturn]] void pgWriter(const std::string& uri, int child, int rows, int batch, const std::string& ids_file) {
  int status = 0;
  try {
    std::mt19937_64 rng(static_cast<std::uint64_t>(1000 + child));
    ExperienceStore store(uri);
    std::ofstream ids(ids_file);
    for (int i = 0; i < rows; i += batch) {
      std::vector<Experience> b;
      for (int j = 0; j < batch; ++j) {
        Experience e = pgSample(rng);
        e.solve_time_s = child * 100000 + i + j;
        b.push_back(std::move(e));
      }
      for (const auto& id : store.insertAll(b, -1.0)) ids << *id << "\n";
      ids.flush();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "writer %d: %s\n", child, e.what());
    status = 1;
  }
  std::fflush(nullptr);
  _exit(status);
}

}  // namespace

TEST_CASE("PostgreSQL: the embedded migrations are byte for byte migrations/postgresql/") {
  const std::filesystem::path dir = std::filesystem::path(EARC_SOURCE_DIR) / "migrations" / "postgresql";
  std::set<std::string> files, embedded;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".sql") files.insert(entry.path().filename().string());
  int expected = 1;
  for (const Migration& m : pgMigrations()) {
    CHECK(m.version == expected++);
    embedded.insert(std::string(m.name));
    CHECK_MESSAGE(pgFileText(dir / m.name) == m.sql, "migration " << m.name << " differs from its file");
  }
  CHECK(files == embedded);
}

TEST_CASE("PostgreSQL: a store is created from empty and migrated from every version" * doctest::skip()) {
  const std::string uri = freshDatabase();
  {
    ExperienceStore store(uri);
    CHECK(store.isPostgres());
    CHECK(store.schemaVersion() == pgCurrentSchemaVersion());
    CHECK(store.session() == 1);
    const HistoryTail h = store.readHistoryLines(10);
    REQUIRE(h.lines.size() == 1);
    CHECK(h.lines[0].operation == "create");
  }
  {
    ExperienceStore again(uri);  // nothing to migrate; a second session
    CHECK(again.session() == 2);
    CHECK(again.readHistoryLines(10).total == 1);
  }
  // From every older version: the database stopped there, then opened.
  for (int from = 1; from < pgCurrentSchemaVersion(); ++from) {
    const std::string old = freshDatabase();
    {
      PgConnection db(old);
      CHECK(pgMigrate(db, from) == from);
      CHECK(pgCheckIdentity(db) == from);
    }
    ExperienceStore store(old);
    CHECK(store.schemaVersion() == pgCurrentSchemaVersion());
    std::mt19937_64 rng(3);
    CHECK(store.insert(pgSample(rng), -1).has_value());
  }
}

TEST_CASE("PostgreSQL: a newer, a foreign and an empty database are refused in one line" * doctest::skip()) {
  const std::string uri = freshDatabase();
  { ExperienceStore store(uri); }
  {
    PgConnection db(uri);
    db.exec("UPDATE earc.store_meta SET value = value + 1 WHERE name = 'schema_version'");
  }
  try {
    ExperienceStore store(uri);
    FAIL("a newer schema was opened");
  } catch (const SchemaVersionError& e) {
    CHECK(std::string(e.what()).find(uri + ": schema version") == 0);
    CHECK(std::string(e.what()).find('\n') == std::string::npos);
  }
  const std::string foreign = freshDatabase();
  {
    PgConnection db(foreign);
    db.exec("CREATE TABLE invoices (id integer)");
  }
  CHECK_THROWS_AS(ExperienceStore{foreign}, ForeignDatabaseError);
  CHECK(pgRows(uri) == 0);  // nothing written to the newer one either
  const std::string empty = freshDatabase();
  CHECK_THROWS_AS((ExperienceStore{empty, wholeFileStoreOptions(true)}), InputError);
  PgConnection db(empty);
  CHECK(db.query("SELECT count(*) FROM pg_namespace WHERE nspname = 'earc'").int64At(0, 0) == 0);
}

TEST_CASE("PostgreSQL: an unreachable server and a password in the URI are one-line errors" * doctest::skip()) {
  try {
    ExperienceStore store("postgresql://earc@127.0.0.1:1/earc");
    FAIL("connected to port 1");
  } catch (const StoreError& e) {
    const std::string what = e.what();
    CHECK(what.find("postgresql://earc@127.0.0.1:1/earc: cannot connect: ") == 0);
    CHECK(what.find('\n') == std::string::npos);
  }
  try {
    ExperienceStore store("postgresql://earc:s3cret-pw@127.0.0.1:1/earc");
    FAIL("a password in the URI was taken");
  } catch (const StoreError& e) {
    const std::string what = e.what();
    CHECK(what.find("s3cret-pw") == std::string::npos);
    CHECK(what.find("postgresql://earc:***@127.0.0.1:1/earc") == 0);
  }
  CHECK(maskedLocation("postgresql://u:pw@h:1/d?password=x&sslmode=require") ==
        "postgresql://u:***@h:1/d?password=***&sslmode=require");
}

TEST_CASE("PostgreSQL: inserted rows are retrieved unchanged, near duplicates refused" * doctest::skip()) {
  const std::string uri = freshDatabase();
  std::mt19937_64 rng(7);
  ExperienceStore store(uri);
  Experience e = pgSample(rng);
  e.solve_time_s = 0.25;
  const auto id = store.insert(e, 0.0);
  REQUIRE(id.has_value());
  CHECK_FALSE(store.insert(e, 0.0).has_value());  // the same key: a near duplicate
  for (int i = 0; i < 30; ++i) store.insert(pgSample(rng), -1);
  const std::vector<Match> found = store.nearest(e.cls, e.key, 10);
  REQUIRE(found.size() == 10);
  CHECK(found[0].distance == 0.0);
  const Experience& got = found[0].experience;
  CHECK(got.id == *id);
  CHECK(got.key == e.key);
  CHECK(got.paths == e.paths);
  CHECK(got.cost == e.cost);
  CHECK(got.solve_time_s == 0.25);
  CHECK(got.created_session == store.session());
  for (std::size_t i = 1; i < found.size(); ++i) CHECK(found[i - 1].distance <= found[i].distance);
  store.recordUse(*id, true);
  store.flush();
  CHECK(store.get(*id)->retrieved == 1);
  CHECK(store.get(*id)->succeeded == 1);
  // Another connection (another planner) sees the rows, and this one sees
  // its rows after a refresh.
  ExperienceStore other(uri);
  CHECK(other.size() == 31);
  const auto more = other.insert(pgSample(rng), -1);
  store.refresh();
  CHECK(store.size() == 32);
  CHECK(store.get(*more).has_value());
}

TEST_CASE("PostgreSQL: a dropped connection is made again for the next insert and retrieval" * doctest::skip()) {
  const std::string uri = freshDatabase();
  std::mt19937_64 rng(13);
  ExperienceStore store(uri);
  const Experience first = pgSample(rng);
  REQUIRE(store.insert(first, -1).has_value());
  // Every other connection to the database dropped by the server.
  auto dropOthers = [&] {
    PgConnection admin(uri);
    return admin
        .query("SELECT count(pg_terminate_backend(pid))::bigint FROM pg_stat_activity "
               "WHERE datname = current_database() AND pid <> pg_backend_pid()")
        .int64At(0, 0);
  };
  CHECK(dropOthers() == 1);
  const Experience second = pgSample(rng);
  const auto id = store.insert(second, -1);
  REQUIRE(id.has_value());
  CHECK(dropOthers() == 1);
  store.refresh();
  const std::vector<Match> found = store.nearest(second.cls, second.key, 1);
  REQUIRE(found.size() == 1);
  CHECK(found[0].experience.id == *id);
  CHECK(pgRows(uri) == 2);  // each once
}

TEST_CASE("PostgreSQL: export, import into SQLite and back round-trip exactly" * doctest::skip()) {
  ScratchDirectory dir("pg");
  const std::string uri = freshDatabase();
  std::mt19937_64 rng(11);
  {
    ExperienceStore store(uri);
    std::vector<Experience> batch;
    for (int i = 0; i < 40; ++i) batch.push_back(pgSample(rng, 2 + i % 2));
    store.insertAll(batch, -1);
    store.recordUse(3, true);
  }
  const std::string a = dir.file("a.jsonl"), b = dir.file("b.jsonl"), c = dir.file("c.jsonl");
  CHECK(exportJsonl(uri, a) == 40);
  {
    ExperienceStore file(dir.file("e.db"));
    CHECK(importInto(file, {a}).inserted == 40);
  }
  CHECK(exportJsonl(dir.file("e.db"), b) == 40);
  CHECK(pgFileText(a) == pgFileText(b));
  const std::string back = freshDatabase();
  {
    ExperienceStore store(back);
    CHECK(importInto(store, {b}).inserted == 40);
  }
  CHECK(exportJsonl(back, c) == 40);
  CHECK(pgFileText(a) == pgFileText(c));
  // A store is an import source too (curate --merge, import).
  CHECK(readImportSource(uri).size() == 40);
  const VerifyReport v = verifyDatabase(back);
  CHECK(v.ok());
  CHECK(v.rows == 40);
}

TEST_CASE("PostgreSQL: two writer processes lose and duplicate no row" * doctest::skip()) {
  ScratchDirectory dir("pg");
  const std::string uri = freshDatabase();
  { ExperienceStore create(uri); }
  constexpr int kRows = 150;
  std::vector<pid_t> children;
  for (int child = 0; child < 2; ++child) {
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) pgWriter(uri, child, kRows, 1, dir.file("ids" + std::to_string(child)));
    children.push_back(pid);
  }
  for (pid_t pid : children) {
    int status = 0;
    waitpid(pid, &status, 0);
    CHECK((WIFEXITED(status) && WEXITSTATUS(status) == 0));
  }
  std::set<std::int64_t> reported;
  for (int child = 0; child < 2; ++child) {
    std::ifstream in(dir.file("ids" + std::to_string(child)));
    for (std::int64_t id; in >> id;) CHECK(reported.insert(id).second);
  }
  CHECK(reported.size() == 2 * kRows);
  PgConnection db(uri);
  CHECK(db.query("SELECT count(*) FROM earc.experiences").int64At(0, 0) == 2 * kRows);
  CHECK(db.query("SELECT count(DISTINCT solve_time_s) FROM earc.experiences").int64At(0, 0) == 2 * kRows);
  std::vector<std::int64_t> ids(reported.begin(), reported.end());
  CHECK(db.query("SELECT count(*) FROM earc.experiences WHERE id = ANY($1)", PgParams().addIds(ids)).int64At(0, 0) ==
        2 * kRows);
  CHECK(db.query("SELECT sum(rows_added)::bigint FROM earc.history WHERE operation = 'learn'").int64At(0, 0) ==
        2 * kRows);
}

TEST_CASE("PostgreSQL: a writer killed mid-transaction leaves whole batches only" * doctest::skip()) {
  ScratchDirectory dir("pg");
  const std::string uri = freshDatabase();
  { ExperienceStore create(uri); }
  constexpr int kBatch = 40;
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) pgWriter(uri, 0, 1000000, kBatch, dir.file("ids"));
  // Killed once it has committed a few batches, most likely mid-batch.
  for (int i = 0; i < 200 && pgRows(uri) < 3 * kBatch; ++i) usleep(20000);
  usleep(7000);
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  CHECK(WIFSIGNALED(status));
  const std::int64_t rows = pgRows(uri);
  CHECK(rows >= 3 * kBatch);
  CHECK(rows % kBatch == 0);
  const VerifyReport v = verifyDatabase(uri);
  CHECK(v.ok());
  CHECK(v.notes.empty());  // the history counts exactly the committed rows
  ExperienceStore after(uri);  // and the store opens and takes rows
  std::mt19937_64 rng(5);
  CHECK(after.insert(pgSample(rng), -1).has_value());
}

TEST_CASE("PostgreSQL: the row cache follows rows committed and deleted by others, within its bound" *
          doctest::skip()) {
  test::checkRowCacheFollowsStore(freshDatabase());
}

TEST_CASE("PostgreSQL: a store that fits the row cache is read whole at open and kept so" * doctest::skip()) {
  const std::string uri = freshDatabase();
  std::mt19937_64 rng(31);
  const std::vector<Experience> rows = pgSamples(rng, 20);
  ExperienceStore writer(uri);
  writer.insertAll(rows, -1.0);
  ExperienceStore reader(uri);
  CHECK(reader.rowCacheSize().first == 20);
  for (const Experience& e : rows) {
    const std::vector<Match> got = reader.nearest(e.cls, e.key, 1);
    REQUIRE(got.size() == 1);
    CHECK(got[0].experience.paths == e.paths);
  }
  // A row another connection commits, and one the reader learns: cached too.
  const Experience later = pgSample(rng);
  const std::int64_t later_id = *writer.insert(later, -1.0);
  std::this_thread::sleep_for(kPgPollInterval + std::chrono::milliseconds(20));
  const Experience own = pgSample(rng);
  const std::int64_t own_id = *reader.insert(own, -1.0);
  CHECK(reader.nearest(later.cls, later.key, 1).at(0).experience.id == later_id);
  CHECK(reader.nearest(own.cls, own.key, 1).at(0).experience.id == own_id);
  CHECK(reader.nearest(own.cls, own.key, 1).at(0).experience.paths == own.paths);
  CHECK(reader.retrievalStats().cache_misses == 0);
  CHECK(reader.rowCacheSize().first == 22);

  // A bound the table does not fit in half of: rows are fetched when missed.
  StoreOptions small;
  small.row_cache_bytes = 16 * 1024;
  ExperienceStore fetching(uri, small);
  CHECK(fetching.rowCacheSize().first == 0);
  CHECK(fetching.nearest(own.cls, own.key, 1).at(0).experience.id == own_id);
  CHECK(fetching.retrievalStats().cache_misses == 1);
}

namespace {

// Every field alike, usage counters included.
void checkSameRow(const Experience& a, const Experience& b) {
  CHECK(a.id == b.id);
  CHECK(a.cls == b.cls);
  CHECK(a.key == b.key);
  CHECK(a.paths == b.paths);
  CHECK(a.cost == b.cost);
  CHECK(a.source == b.source);
  CHECK(a.created_at == b.created_at);
  CHECK(a.solve_time_s == b.solve_time_s);
  CHECK(a.retrieved == b.retrieved);
  CHECK(a.succeeded == b.succeeded);
  CHECK(a.created_session == b.created_session);
  CHECK(a.made_by == b.made_by);
}

// The bytes PgWarmRows holds for the whole store at `uri`.
std::size_t pgWarmBytesHeld(const std::string& uri) {
  PgWarmRows all(uri, std::size_t{1} << 40);
  REQUIRE(all.awaitRead() == static_cast<std::size_t>(pgRows(uri)));
  return all.bytes();
}

}  // namespace

TEST_CASE("PostgreSQL: the background copy packs rows exactly, damaged ones to fail as the server's" *
          doctest::skip()) {
  const std::string uri = freshDatabase();
  std::mt19937_64 rng(43);
  const std::vector<Experience> rows = pgSamples(rng, 120, 3);
  {
    ExperienceStore writer(uri);
    writer.insertAll(rows, -1.0);
  }
  PgConnection admin(uri);
  // A key a little off its paths' endpoints (within findProblem's
  // tolerance), odd counters and times, and rows the checks refuse.
  admin.exec("UPDATE earc.experiences SET retrieved_count = 1099511627776, succeeded_count = 3, "
             "created_at = 0, solve_time_s = 1e-300, made_by = '' WHERE id % 7 = 0");
  const std::int64_t first = admin.query("SELECT min(id) FROM earc.experiences").int64At(0, 0);
  const Experience off = *ExperienceStore(uri).get(first + 1);
  std::vector<double> key = off.key;
  key[0] += 5e-7;
  admin.query("UPDATE earc.experiences SET key = $1 WHERE id = $2",
              PgParams().addBytes(encodeKey(key)).add(first + 1));
  admin.query("UPDATE earc.experiences SET key = '\\x000102' WHERE id = $1", PgParams().add(first + 2));
  admin.query("UPDATE earc.experiences SET paths = '\\x00' WHERE id = $1", PgParams().add(first + 3));
  admin.query("UPDATE earc.experiences SET cost = cost + 1 WHERE id = $1", PgParams().add(first + 4));

  const PgResult all = admin.query(pgSelectExperiencesSql() + " ORDER BY id");
  PgWarmStringNumbers numbers;
  std::vector<unsigned char> bytes;
  std::vector<std::size_t> at;
  for (int i = 0; i < all.rows(); ++i) {
    at.push_back(bytes.size());
    packPgWarmRow(all, i, numbers, bytes);
  }
  const std::vector<std::string> strings = numbers.takeAdded();
  CHECK(strings.size() == 5);  // three signatures, "" and the build, each once
  std::size_t sent = 0;
  for (int i = 0; i < all.rows(); ++i)
    for (int c = 0; c < kPgRowColumns; ++c) sent += all.bytesAt(i, c).size();
  CHECK(bytes.size() < sent * 3 / 4);
  int damaged = 0;
  for (int i = 0; i < all.rows(); ++i) {
    const std::int64_t id = all.int64At(i, 0);
    std::string want, got;
    try {
      const Experience e = readPgExperience(all, i);
      checkSameRow(unpackPgWarmRow(id, bytes.data() + at[static_cast<std::size_t>(i)], strings), e);
      continue;
    } catch (const CorruptRowError& e) {
      want = e.what();
    }
    ++damaged;
    try {
      unpackPgWarmRow(id, bytes.data() + at[static_cast<std::size_t>(i)], strings);
    } catch (const CorruptRowError& e) {
      got = e.what();
    }
    CHECK(got == want);
  }
  CHECK(damaged == 3);

  // The estimate from a sample of pages, against the bytes held.
  const std::size_t held = pgWarmBytesHeld(uri);
  const std::size_t estimate = estimatePgWarmBytes(admin, rows.size());
  CHECK(estimate > held * 4 / 5);
  CHECK(estimate < held * 5 / 4);
}

TEST_CASE("PostgreSQL: closing a store stops its background read at once" * doctest::skip()) {
  const std::string uri = freshDatabase();
  std::mt19937_64 rng(47);
  const std::vector<Experience> rows = pgSamples(rng, 50);
  ExperienceStore(uri).insertAll(rows, -1.0);
  // The reading waits for a lock held for 30 s; stopping it cancels the
  // statement, whenever it comes.
  PgConnection locker(uri);
  locker.exec("BEGIN");
  locker.exec("LOCK TABLE earc.experiences IN ACCESS EXCLUSIVE MODE");
  std::promise<void> done;
  std::thread release([&, stopped = done.get_future()] {
    stopped.wait_for(std::chrono::seconds(30));
    locker.exec("ROLLBACK");
  });
  for (int wait_ms : {0, 300}) {
    const auto t0 = std::chrono::steady_clock::now();
    {
      PgWarmRows reading(uri, std::size_t{1} << 30);
      std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
    }
    CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(10));
  }
  done.set_value();
  release.join();
}

TEST_CASE("PostgreSQL: a store larger than half the row cache is read in the background, then served from memory" *
          doctest::skip()) {
  const std::string uri = freshDatabase();
  std::mt19937_64 rng(41);
  const std::vector<Experience> rows = pgSamples(rng, 200, 2);
  std::vector<std::int64_t> ids;
  {
    ExperienceStore writer(uri);
    for (const auto& id : writer.insertAll(rows, -1.0)) ids.push_back(*id);
    writer.recordUse(ids[7], true);
  }
  // A bound whose half the table exceeds (no read at open) and that holds
  // every packed row.
  PgConnection admin(uri);
  const auto table = static_cast<std::size_t>(
      admin.query("SELECT pg_total_relation_size('earc.experiences')").int64At(0, 0));
  const std::size_t packed = pgWarmBytesHeld(uri);
  StoreOptions opts;
  opts.row_cache_bytes = 2 * table - 1;
  REQUIRE_MESSAGE(opts.row_cache_bytes >= packed, "packed rows " << packed << ", table " << table);

  ExperienceStore warm(uri, opts);
  CHECK(warm.rowCacheSize().first == 0);
  CHECK(warm.awaitWarmRows() == 200);
  StoreOptions cold_opts = opts;
  cold_opts.warm_rows = false;
  ExperienceStore cold(uri, cold_opts);
  CHECK(cold.awaitWarmRows() == 0);

  // The same rows, byte for byte, as the server's.
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::vector<Match> a = warm.nearest(rows[i].cls, rows[i].key, 1);
    const std::vector<Match> b = cold.nearest(rows[i].cls, rows[i].key, 1);
    REQUIRE(a.size() == 1);
    REQUIRE(b.size() == 1);
    CHECK(a[0].experience.id == ids[i]);
    checkSameRow(a[0].experience, b[0].experience);
  }
  CHECK(warm.retrievalStats().warm_hits == 200);
  CHECK(cold.retrievalStats().warm_hits == 0);

  // From memory, not the server: rows changed behind the stores' backs
  // come unchanged from a new open's copy, changed from the server. A
  // deletion (counted) empties the copy.
  ExperienceStore again(uri, opts);
  CHECK(again.awaitWarmRows() == 200);
  ExperienceStore fetching(uri, cold_opts);
  admin.exec("UPDATE earc.experiences SET made_by = 'changed behind its back'");
  for (std::size_t i = 0; i < rows.size(); i += 20) {
    CHECK(again.nearest(rows[i].cls, rows[i].key, 1).at(0).experience.made_by == rows[i].made_by);
    CHECK(fetching.nearest(rows[i].cls, rows[i].key, 1).at(0).experience.made_by == "changed behind its back");
  }
  admin.exec("DELETE FROM earc.experiences WHERE id = " + std::to_string(ids[1]));
  std::this_thread::sleep_for(kPgPollInterval + std::chrono::milliseconds(20));
  CHECK(again.nearest(rows[1].cls, rows[1].key, 1).at(0).experience.id != ids[1]);
  CHECK(again.awaitWarmRows() == 0);
  CHECK(again.nearest(rows[2].cls, rows[2].key, 1).at(0).experience.made_by == "changed behind its back");

  // A bound too small for the store: no copy (not even read), every row
  // from the server.
  const std::string other = freshDatabase();
  ExperienceStore(other).insertAll(rows, -1.0);
  StoreOptions small = opts;
  small.row_cache_bytes = packed / 2;
  ExperienceStore part(other, small);
  CHECK(part.awaitWarmRows() == 0);
  for (const Experience& e : rows) CHECK(part.nearest(e.cls, e.key, 1).at(0).experience.paths == e.paths);
  CHECK(part.retrievalStats().warm_hits == 0);
  CHECK(part.rowCacheSize().second > small.row_cache_bytes / 4);
  CHECK(part.rowCacheSize().second <= small.row_cache_bytes);
}
