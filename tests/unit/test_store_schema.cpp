// Schema, identity and migrations of the experience database.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "earc/experience/path_blob.hpp"
#include "earc/experience/sampling.hpp"
#include "earc/experience/schema.hpp"
#include "earc/experience/scratch.hpp"
#include "earc/experience/store.hpp"
#include "support.hpp"

using earc::test::discTraits;
using earc::test::readFile;
using earc::test::readOnly;

using namespace earc;
using namespace earc::exp;

namespace {

std::string collapseSpace(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (std::isspace(static_cast<unsigned char>(c))) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

// Everything about a schema that matters to a program: identity, every
// table's columns (name, type, not-null, default, key), every index's
// columns and uniqueness, every trigger's text, and store_meta's rows.
std::string describe(Connection& db) {
  std::ostringstream out;
  out << "application_id " << db.pragmaInt("application_id") << "\nuser_version " << db.pragmaInt("user_version")
      << "\n";
  Statement objects = db.prepare("SELECT type, name, sql FROM sqlite_schema ORDER BY type, name");
  std::vector<std::tuple<std::string, std::string, std::string>> list;
  while (objects.step()) list.emplace_back(objects.textAt(0), objects.textAt(1), objects.textAt(2));
  for (const auto& [type, name, sql] : list) {
    out << type << " " << name << "\n";
    if (type == "table") {
      Statement cols = db.prepare("SELECT cid, name, type, \"notnull\", dflt_value, pk FROM pragma_table_xinfo(?1)");
      cols.bind(1, std::string_view(name));
      while (cols.step())
        out << "  col " << cols.int64At(0) << " " << cols.textAt(1) << " " << cols.textAt(2) << " nn="
            << cols.int64At(3) << " default=" << cols.textAt(4) << " pk=" << cols.int64At(5) << "\n";
    } else if (type == "index") {
      Statement cols = db.prepare("SELECT seqno, name FROM pragma_index_info(?1)");
      cols.bind(1, std::string_view(name));
      while (cols.step()) out << "  key " << cols.int64At(0) << " " << cols.textAt(1) << "\n";
    } else if (type == "trigger") {
      out << "  " << collapseSpace(sql) << "\n";
    }
  }
  Statement meta = db.prepare("SELECT name, value FROM store_meta ORDER BY name");
  while (meta.step()) out << "meta " << meta.textAt(0) << "=" << meta.int64At(1) << "\n";
  return out.str();
}

Experience sample(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<RobotTraits> robots{discTraits(), discTraits()};
  return straightLineExperience(robots, sampleMobileQuery(2, rng), 6);
}

// A file at schema version `version` (0: an empty SQLite file), with one
// row when the version has the experiences table.
void makeFileAtVersion(const std::string& path, int version) {
  Connection c(path, OpenMode::ReadWrite);
  c.enableWal();
  if (version == 0) return;
  REQUIRE(migrate(c, version) == version);
  Experience e = sample(1);
  Statement ins = c.prepare(
      "INSERT INTO experiences (kind, robot_count, signature, base_class, key, paths, cost, source, created_at) "
      "VALUES ('mobile', 2, ?1, '', ?2, ?3, ?4, 'build', 1700000000)");
  ins.bind(1, std::string_view(e.cls.signature)).bindBlob(2, encodeKey(e.key)).bindBlob(3, encodePathsV2(e.paths));
  ins.bind(4, e.cost);
  ins.run();
}

template <class Error>
std::string openError(const std::string& path, StoreOptions options = {}) {
  try {
    ExperienceStore store(path, options);
  } catch (const Error& e) {
    return e.what();
  }
  FAIL("no error opening " << path);
  return "";
}

}  // namespace

TEST_CASE("the embedded migrations are byte for byte the files in migrations/") {
  const std::filesystem::path dir = std::filesystem::path(EARC_SOURCE_DIR) / "migrations";
  std::set<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".sql") files.insert(entry.path().filename().string());
  std::set<std::string> embedded;
  int expected_version = 1;
  for (const Migration& m : migrations()) {
    CHECK(m.version == expected_version++);
    embedded.insert(std::string(m.name));
    CHECK_MESSAGE(readFile(dir / m.name) == m.sql, "migration " << m.name << " differs from its file");
  }
  CHECK(files == embedded);
  CHECK(currentSchemaVersion() >= 2);
}

TEST_CASE("schema.sql describes exactly what the migrations create") {
  Connection migrated(":memory:", OpenMode::Memory);
  migrate(migrated);
  Connection documented(":memory:", OpenMode::Memory);
  documented.exec(readFile(std::filesystem::path(EARC_SOURCE_DIR) / "schema" / "schema.sql"));
  CHECK(describe(documented) == describe(migrated));
  CHECK(describe(migrated).find("col 13 created_session") != std::string::npos);
  CHECK(describe(migrated).find("col 14 made_by") != std::string::npos);
}

TEST_CASE("a new file is created at the current version with the EARC application id and WAL") {
  ScratchDirectory dir("schema");
  const std::string path = dir.file("new.db");
  {
    ExperienceStore store(path);
    CHECK(store.schemaVersion() == currentSchemaVersion());
    CHECK(store.session() == 1);
  }
  Connection c(path, OpenMode::ReadOnly);
  CHECK(c.pragmaInt("application_id") == kApplicationId);
  CHECK(c.pragmaInt("user_version") == currentSchemaVersion());
  CHECK(c.pragmaText("journal_mode") == "wal");
}

TEST_CASE("a file at every earlier schema version is migrated to the current one and keeps its rows") {
  ScratchDirectory dir("schema");
  // A planner's open (quick_check in the background) migrates too: only a
  // file at the current version leaves the check for later.
  for (int v = 0; v < currentSchemaVersion(); ++v)
    for (bool background : {false, true}) {
      CAPTURE(v);
      CAPTURE(background);
      const std::string path = dir.file(std::to_string(v) + (background ? "-bg" : "") + "-version.db");
      makeFileAtVersion(path, v);
      StoreOptions options;
      options.check_in_background = background;
      ExperienceStore store(path, options);
      CHECK(store.schemaVersion() == currentSchemaVersion());
      CHECK(store.size() == (v >= 1 ? 1u : 0u));
      // The history says who created or migrated the file, and from what.
      const HistoryTail history = readHistory(store.connection(), store.schemaVersion(), 10);
      // A file made at version 5 or later (with a history) has its own
      // creation line before it.
      REQUIRE(history.lines.size() == (v >= 5 ? 2u : 1u));
      CHECK(history.lines.back().operation == (v == 0 ? "create" : "migrate"));
      const std::string now = std::to_string(currentSchemaVersion());
      CHECK(history.lines.back().detail == (v == 0 ? "schema " + now : "schema " + std::to_string(v) + " to " + now));
      if (v >= 1) {
        auto row = store.get(1);
        REQUIRE(row.has_value());
        CHECK(row->paths == sample(1).paths);
        CHECK(row->retrieved == 0);
        CHECK(row->created_at == 1700000000);
        CHECK(row->made_by.empty());  // stored before version 4: not known
      }
    }
}

TEST_CASE("an older file can be read without migrating it when opened read-only") {
  ScratchDirectory dir("schema");
  const std::string path = dir.file("v1.db");
  makeFileAtVersion(path, 1);
  {
    ExperienceStore store(path, readOnly());
    CHECK(store.schemaVersion() == 1);
    CHECK(store.size() == 1);
    CHECK(store.get(1)->paths == sample(1).paths);
  }
  Connection c(path, OpenMode::ReadOnly);
  CHECK(c.pragmaInt("user_version") == 1);
}

TEST_CASE("a migration that fails leaves the file at its previous version") {
  ScratchDirectory dir("schema");
  const std::string path = dir.file("v1.db");
  makeFileAtVersion(path, 1);
  {
    Connection c(path, OpenMode::ReadWrite);
    c.exec("CREATE TABLE store_meta (x)");  // migration 2 creates store_meta too
  }
  CHECK(openError<StoreError>(path).find("store_meta") != std::string::npos);
  Connection c(path, OpenMode::ReadOnly);
  CHECK(c.pragmaInt("user_version") == 1);
  Statement cols = c.prepare("SELECT count(*) FROM pragma_table_info('experiences') WHERE name = 'solve_time_s'");
  cols.step();
  CHECK(cols.int64At(0) == 0);  // the ALTERs of migration 2 were rolled back
}

TEST_CASE("a foreign SQLite file is refused naming its application id, and left untouched") {
  ScratchDirectory dir("schema");
  const std::string path = dir.file("foreign.db");
  {
    Connection c(path, OpenMode::ReadWrite);
    c.exec("PRAGMA application_id = 305419896; CREATE TABLE photos (id INTEGER PRIMARY KEY)");
  }
  std::string msg = openError<ForeignDatabaseError>(path);
  CHECK(msg.find("not an earc experience database") != std::string::npos);
  CHECK(msg.find("0x12345678") != std::string::npos);
  CHECK(msg.find("0x45415243") != std::string::npos);
  Connection c(path, OpenMode::ReadOnly);
  CHECK(c.pragmaText("journal_mode") == "delete");  // not switched to WAL
  CHECK(c.pragmaInt("user_version") == 0);
}

TEST_CASE("a SQLite file of another program without an application id is refused") {
  ScratchDirectory dir("schema");
  const std::string path = dir.file("plain.db");
  {
    Connection c(path, OpenMode::ReadWrite);
    c.exec("CREATE TABLE notes (body TEXT)");
  }
  CHECK(openError<ForeignDatabaseError>(path).find("application_id 0x00000000") != std::string::npos);
}

TEST_CASE("a file that is not SQLite at all is refused as such") {
  ScratchDirectory dir("schema");
  const std::string path = dir.file("text.db");
  std::ofstream(path) << "this is not a database, just some text that is long enough to fill a header........\n";
  CHECK(openError<ForeignDatabaseError>(path).find("not a SQLite database") != std::string::npos);
}

TEST_CASE("a file with a newer schema version is refused naming both versions") {
  ScratchDirectory dir("schema");
  const std::string path = dir.file("newer.db");
  makeFileAtVersion(path, currentSchemaVersion());
  const int newer = currentSchemaVersion() + 1;
  {
    Connection c(path, OpenMode::ReadWrite);
    c.exec("PRAGMA user_version = " + std::to_string(newer));
  }
  try {
    ExperienceStore store(path);
    FAIL("opened a newer file");
  } catch (const SchemaVersionError& e) {
    CHECK(e.fileVersion() == newer);
    CHECK(e.programVersion() == currentSchemaVersion());
    const std::string msg = e.what();
    CHECK(msg.find("schema version " + std::to_string(newer)) != std::string::npos);
    CHECK(msg.find("program's version " + std::to_string(currentSchemaVersion())) != std::string::npos);
  }
  CHECK(openError<SchemaVersionError>(path, readOnly()).find("newer") != std::string::npos);
}
