// The experience database's history: one line per open that changed the
// file, counting in the same transaction exactly the rows it committed.
#include <doctest/doctest.h>

#include <fstream>
#include <random>

#include "earc/experience/history.hpp"
#include "earc/experience/maintenance.hpp"
#include "earc/experience/sampling.hpp"
#include "earc/experience/schema.hpp"
#include "earc/experience/scratch.hpp"
#include "earc/experience/store.hpp"
#include "earc/experience/transfer.hpp"
#include "earc/methods/builder.hpp"
#include "earc/util/version.hpp"
#include "support.hpp"

using earc::test::discTraits;

using namespace earc;
using namespace earc::exp;

namespace {

Experience historySample(std::mt19937_64& rng, int robots = 2) {
  const std::vector<RobotTraits> traits(static_cast<std::size_t>(robots), discTraits(0.3));
  return straightLineExperience(traits, sampleMobileQuery(robots, rng), 6);
}

std::vector<HistoryLine> historyOf(const std::string& path) {
  Connection c(path, OpenMode::ReadOnly);
  return readHistory(c, currentSchemaVersion(), 1000).lines;
}

std::int64_t historyRowCount(const std::string& path) {
  Connection c(path, OpenMode::ReadOnly);
  Statement s = c.prepare("SELECT count(*) FROM experiences");
  s.step();
  return s.int64At(0);
}

}  // namespace

TEST_CASE("a new file's history starts with its creation by this build") {
  ScratchDirectory dir("history");
  const std::string path = dir.file("h.db");
  { ExperienceStore store(path); }
  { ExperienceStore again(path); }  // opens that change nothing write no line
  auto lines = historyOf(path);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].operation == "create");
  CHECK(lines[0].detail == "schema " + std::to_string(currentSchemaVersion()));
  CHECK(lines[0].program == version());
  CHECK(lines[0].at > 1700000000);
  CHECK(lines[0].rows_added == 0);
}

TEST_CASE("each open's inserts are counted on its own line; a rolled-back insert counts nothing") {
  ScratchDirectory dir("history");
  const std::string path = dir.file("h.db");
  std::mt19937_64 rng(3);
  const Experience twin = historySample(rng);
  {
    ExperienceStore store(path);  // planning session 1
    REQUIRE(store.insert(twin, 1e-6));
    CHECK_FALSE(store.insert(twin, 1e-6));  // a near duplicate: not stored, not counted
    auto ids = store.insertAll({historySample(rng), historySample(rng), twin}, 1e-6);
    CHECK(ids[0].has_value());
    CHECK_FALSE(ids[2].has_value());
    // A batch that fails inside its transaction, after its first row was
    // inserted and counted (a trigger refuses the second): nothing of it
    // is stored or counted...
    {
      Connection other(path, OpenMode::ReadWrite);
      other.exec("CREATE TRIGGER refuse BEFORE INSERT ON experiences WHEN NEW.solve_time_s = 99 "
                 "BEGIN SELECT RAISE(ABORT, 'refused by the test'); END");
    }
    Experience refused = historySample(rng);
    refused.solve_time_s = 99;
    CHECK_THROWS_AS(store.insertAll({historySample(rng), refused}, 1e-6), StoreError);
    {
      Connection other(path, OpenMode::ReadWrite);
      other.exec("DROP TRIGGER refuse");
    }
    // ...and the line is still this open's after the rollback.
    REQUIRE(store.insert(historySample(rng), 1e-6));
  }
  {
    ExperienceStore store(path);  // session 2
    store.describeHistory("import", "from a test");
    REQUIRE(store.insert(historySample(rng, 3), -1));
  }
  auto lines = historyOf(path);
  REQUIRE(lines.size() == 3);
  CHECK(lines[1].operation == "learn");
  CHECK(lines[1].detail == "planning session 1");
  CHECK(lines[1].rows_added == 4);
  CHECK(lines[2].operation == "import");
  CHECK(lines[2].detail == "from a test");
  CHECK(lines[2].rows_added == 1);
  CHECK(historyRowCount(path) == 5);
}

TEST_CASE("build, import and curate write what they did; the counts add up to the rows") {
  ScratchDirectory dir("history");
  const std::string built = dir.file("built.db"), copy = dir.file("copy.db"), exported = dir.file("rows.jsonl");
  BuildReport b;
  {
    ExperienceStore store(built, wholeFileStoreOptions(false));
    BuildSettings s;
    s.count = 8;
    s.seed = 5;
    b = buildDatabase(store, s);
  }
  REQUIRE(b.inserted > 0);
  auto lines = historyOf(built);
  REQUIRE(lines.size() == 2);
  CHECK(lines[1].operation == "build");
  CHECK(lines[1].detail.find("8 mobile problems, seed 5") == 0);
  // Which draw made the rows (earlier builds crossed every robot over the
  // conflict point and said nothing of it).
  CHECK(lines[1].detail.find(" s a problem, robots rest 0.15 or pass within 0.5") != std::string::npos);
  CHECK(lines[1].rows_added == b.inserted);

  CurateSettings c;
  c.dedupe_eps = 1e9;  // one entry per class is left
  c.output = copy;
  const CurateReport r = curateDatabase(built, c);
  CHECK(historyOf(built).size() == 2);  // the original is untouched
  lines = historyOf(copy);
  REQUIRE(lines.size() == 3);  // the copy carries the original's history
  CHECK(lines[2].operation == "curate");
  CHECK(lines[2].detail == "copy of " + built + ": --dedupe 1e+09");
  CHECK(lines[2].rows_removed == r.duplicates_removed);
  CHECK(r.duplicates_removed > 0);

  CurateSettings nothing;  // a curate that changes no row still says it ran
  curateDatabase(copy, nothing);
  lines = historyOf(copy);
  REQUIRE(lines.size() == 4);
  CHECK(lines[3].operation == "curate");
  CHECK(lines[3].rows_added == 0);
  CHECK(lines[3].rows_removed == 0);

  std::int64_t net = 0;
  for (const HistoryLine& l : lines) net += l.rows_added - l.rows_removed;
  CHECK(net == historyRowCount(copy));

  // An export's rows read the same in programs since the last change of
  // the experiences table: it says that version, not the file's.
  exportJsonl(copy, exported);
  std::ifstream in(exported);
  std::string header;
  std::getline(in, header);
  CHECK(header.find("\"schema_version\":" + std::to_string(kExperienceRowsSchemaVersion)) != std::string::npos);
}

TEST_CASE("inspect shows the last lines of the history, and says none is kept before schema 5") {
  ScratchDirectory dir("history");
  const std::string path = dir.file("h.db");
  std::mt19937_64 rng(9);
  for (int i = 0; i < 3; ++i) {
    ExperienceStore store(path);
    store.insert(historySample(rng), -1);
  }
  InspectReport r = inspectDatabase(path, 1, 2);
  CHECK(r.history.total == 4);
  REQUIRE(r.history.lines.size() == 2);
  CHECK(r.history.lines[0].detail == "planning session 2");
  CHECK(r.history.lines[1].detail == "planning session 3");

  // The same report for scripts.
  const nlohmann::json j = inspectJson(r);
  CHECK(j["format"] == "earc.inspect.v1");
  CHECK(j["entries"] == 3);
  REQUIRE(j["classes"].size() == 1);
  CHECK(j["classes"][0]["entries"] == 3);
  CHECK(j["classes"][0]["robots"] == 2);
  CHECK(j["classes"][0]["hit_rate"].is_null());  // never retrieved
  CHECK(j["builds"][0]["made_by"] == version());
  CHECK(j["history"]["total"] == 4);
  REQUIRE(j["history"]["lines"].size() == 2);
  CHECK(j["history"]["lines"][1]["operation"] == "learn");
  CHECK(j["history"]["lines"][1]["rows_added"] == 1);
  REQUIRE(j["samples"].size() == 1);
  CHECK(j["samples"][0]["id"] == 1);

  const std::string old = dir.file("old.db");
  {
    Connection c(old, OpenMode::ReadWrite);
    c.enableWal();
    migrate(c, kHistorySchemaVersion - 1);
  }
  InspectReport before = inspectDatabase(old, 0);
  CHECK(before.schema_version == kHistorySchemaVersion - 1);
  CHECK(inspectJson(before)["history"].is_null());  // none kept, not an empty one
  CHECK(inspectJson(r)["history"].is_object());
}

TEST_CASE("history details from command lines are kept printable, valid UTF-8 and bounded") {
  ScratchDirectory dir("history");
  const std::string path = dir.file("h.db");
  std::mt19937_64 rng(4);
  {
    ExperienceStore store(path);
    store.describeHistory("import", "from a\nb\x1b[31m\xff\xc3" + std::string(600, 'x'));
    store.insert(historySample(rng), -1);
  }
  const std::string detail = historyOf(path).back().detail;
  CHECK(detail.size() <= kMaxHistoryDetail);
  CHECK(detail.rfind("from a?b?[31m??xxx", 0) == 0);
  CHECK(detail.ends_with("x..."));
}

TEST_CASE("exports say the schema version of the experiences table's columns, unchanged since") {
  // If a migration changes the experiences table, exports must say so:
  // raise kExperienceRowsSchemaVersion with it.
  auto columns = [](int version) {
    Connection c(":memory:", OpenMode::Memory);
    migrate(c, version);
    Statement s = c.prepare("SELECT name, type, \"notnull\", dflt_value FROM pragma_table_info('experiences')");
    std::string out;
    while (s.step()) out += s.textAt(0) + " " + s.textAt(1) + " " + s.textAt(2) + " " + s.textAt(3) + "\n";
    return out;
  };
  CHECK(kExperienceRowsSchemaVersion <= currentSchemaVersion());
  CHECK(columns(kExperienceRowsSchemaVersion) == columns(currentSchemaVersion()));
  CHECK(columns(kExperienceRowsSchemaVersion - 1) != columns(kExperienceRowsSchemaVersion));
}

TEST_CASE("verify notes rows added or deleted outside earc, by the history's count") {
  ScratchDirectory dir("history");
  const std::string path = dir.file("h.db");
  std::mt19937_64 rng(6);
  {
    ExperienceStore store(path);
    store.insertAll({historySample(rng), historySample(rng), historySample(rng)}, -1);
  }
  VerifyReport sound = verifyDatabase(path);
  CHECK(sound.ok());
  CHECK(sound.notes.empty());
  {
    Connection c(path, OpenMode::ReadWrite);
    c.exec("DELETE FROM experiences WHERE id = 2");
  }
  VerifyReport edited = verifyDatabase(path);
  CHECK(edited.ok());  // not damage
  REQUIRE(edited.notes.size() == 1);
  CHECK(edited.notes[0] == "the history counts 3 rows added and not removed, the file holds 2: rows were added or "
                           "deleted outside earc");
}
