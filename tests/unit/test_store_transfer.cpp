// Export, import and verify: moving experiences between files without
// losing, changing or letting in anything bad.
#include <doctest/doctest.h>

#include "store_transfer_fixtures.hpp"

using namespace earc;
using namespace earc::exp;
using namespace earc::store_test;

TEST_CASE("export then import gives the same rows, every double bit for bit") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db"), b = dir.file("b.db"), jsonl = dir.file("a.jsonl");
  fill(a, 1);
  {
    // Rows learned in a later planning session keep that session too.
    RobotSpec disc;
    disc.radius = 0.3;
    const RobotTraits d = traitsOf(*makeRobotModel(disc, Resolution{}));
    std::mt19937_64 rng(2);
    ExperienceStore later(a);
    REQUIRE(later.session() > 0);
    later.insertAll({straightLineExperience(std::vector<RobotTraits>{d, d}, sampleMobileQuery(2, rng), 5)}, -1);
  }
  CHECK(exportJsonl(a, jsonl) == 61);
  ExperienceStore store(b);
  ImportReport r = importInto(store, {jsonl});
  store.close();
  CHECK(r.read == 61);
  CHECK(r.inserted == 61);
  CHECK(contents(b) == contents(a));
  CHECK(contents(b).back()["created_session"].get<std::int64_t>() > 0);
  // The copy has seen as many sessions as its latest row's: curate
  // --older-than-sessions judges both files alike.
  CHECK(ExperienceStore(b, wholeFileStoreOptions(true)).session() ==
        ExperienceStore(a, wholeFileStoreOptions(true)).session());
  // Importing the same export again changes nothing: every row is there.
  {
    ExperienceStore again(b);
    const ImportReport twice = importInto(again, {jsonl});
    CHECK(twice.inserted == 0);
    CHECK(twice.already_stored == 61);
  }
  CHECK(contents(b) == contents(a));
  // Into a file with rows of its own, the rows are new there: this session.
  const std::string c = dir.file("c.db");
  fill(c, 3);  // seed 2 would make the row `later` added above
  std::int64_t session = 0;
  {
    ExperienceStore more(c);
    session = more.session();
    const ImportReport into_other = importInto(more, {jsonl});
    CHECK(into_other.inserted == 61);
    CHECK(into_other.already_stored == 0);
  }
  const auto rows = contents(c);
  REQUIRE(rows.size() == 121);
  for (std::size_t i = 60; i < rows.size(); ++i) CHECK(rows[i]["created_session"].get<std::int64_t>() == session);
  // JSON equality compares doubles exactly; make sure some are not short decimals.
  CHECK(contents(a)[2]["solve_time_s"].get<double>() == 0.1 * 1 / 3.0);
  // Each row keeps the build that made it, known or not.
  CHECK(contents(b)[0]["made_by"] == std::string(version()));
  CHECK(contents(b)[2]["made_by"] == "");
  CHECK(contents(b)[5]["made_by"] == "0.0.9+abc1234");
}

TEST_CASE("an export row without made_by (schema before 4) imports as not known; a bad one is refused") {
  ScratchDirectory dir("transfer");
  const std::string jsonl = dir.file("a.jsonl");
  std::vector<std::string> lines = exportedLines(dir, jsonl, 11);
  nlohmann::json row = nlohmann::json::parse(lines[1]);
  row.erase("made_by");
  lines[1] = row.dump();
  writeLines(jsonl, lines);
  {
    ExperienceStore store(dir.file("b.db"));
    CHECK(importInto(store, {jsonl}).inserted == lines.size() - 1);
    CHECK(store.get(1)->made_by.empty());
  }
  for (const std::string& bad : {std::string("0.1.0\nrm -rf"), std::string(kMaxMadeBy + 1, 'x')}) {
    row["made_by"] = bad;
    lines[1] = row.dump();
    writeLines(jsonl, lines);
    const std::string msg = importError(dir.file("c.db"), {jsonl});
    CHECK(msg.find("line 2") != std::string::npos);
    CHECK(msg.find("made_by") != std::string::npos);
    CHECK(msg.size() < 300);
  }
}

TEST_CASE("an earc database imports directly with the same rows") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db"), b = dir.file("b.db");
  fill(a, 2);
  ExperienceStore store(b);
  CHECK(importInto(store, {a}).inserted == 60);
  store.close();
  CHECK(contents(b) == contents(a));
}

TEST_CASE("an export line with a bad row makes the import apply nothing and names the line") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db"), b = dir.file("b.db"), good = dir.file("good.jsonl"), bad = dir.file("bad.jsonl");
  fill(a, 3);
  exportJsonl(a, good);
  auto lines = readLines(good);
  auto row = nlohmann::json::parse(lines[5]);
  row["paths"][0][1][0] = "oops";
  lines[5] = row.dump();
  writeLines(bad, lines);
  const std::string msg = importError(b, {good, bad});  // the good file first: still nothing applied
  CHECK(msg.find("line 6") != std::string::npos);
  CHECK(msg.find("nothing was imported") != std::string::npos);
  CHECK(rowCount(b) == 0);
}

TEST_CASE("an export row with usage counters or a date no earc file can hold is refused, naming the line") {
  // Counters near 2^63 imported whole once, and the first plan's use then
  // overflowed them into real numbers that verify and export refused;
  // created_at past the year 9999 printed as a garbled date.
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db"), good = dir.file("good.jsonl"), bad = dir.file("bad.jsonl");
  fill(a, 4);
  exportJsonl(a, good);
  const auto lines = readLines(good);
  for (const auto& [field, value, says] :
       {std::tuple<const char*, std::int64_t, const char*>{"retrieved", std::int64_t{1} << 62, "usage counters"},
        {"retrieved", kMaxUseCount + 1, "usage counters"},
        {"created_at", 99999999999999999, "after the year 9999"}}) {
    CAPTURE(field);
    auto changed = lines;
    auto row = nlohmann::json::parse(changed[3]);
    row[field] = value;
    changed[3] = row.dump();
    writeLines(bad, changed);
    const std::string b = dir.file(std::string(field) + std::to_string(value) + ".db");
    const std::string msg = importError(b, {bad});
    CHECK(msg.find("line 4") != std::string::npos);
    CHECK(msg.find(says) != std::string::npos);
    CHECK(rowCount(b) == 0);
  }
}

// Signatures that do not parse, or that disagree with the row's kind or
// dimension, for the rows fill() writes first: a mobile pair (id 1) and an
// arm pair (id 3).
std::vector<std::pair<std::int64_t, std::string>> badSignatures(const std::string& arm_signature) {
  RobotSpec shorter = *robotFromSignature(arm_signature.substr(0, arm_signature.find('|')));
  shorter.links.pop_back();
  shorter.joint_limits.pop_back();
  const std::string short_arm = makeRobotModel(shorter, Resolution{})->geometrySignature();
  return {{1, "mobile:disc:-1|mobile:disc:-1"},
          {1, "mobile:disc:r=0.3|spaceship"},
          {1, "mobile:disc:r=0.3"},
          {1, arm_signature},
          {3, "mobile:disc:r=0.3|mobile:disc:r=0.3"},
          {3, short_arm + "|" + short_arm}};
}

TEST_CASE("an export row whose signature does not parse or disagrees with the row is refused, naming the field") {
  ScratchDirectory dir("transfer");
  const std::string jsonl = dir.file("a.jsonl");
  const auto lines = exportedLines(dir, jsonl, 4);
  const std::string arm_signature = nlohmann::json::parse(lines[3])["signature"];
  for (const auto& [id, signature] : badSignatures(arm_signature)) {
    CAPTURE(signature);
    auto changed = lines;
    auto row = nlohmann::json::parse(changed[static_cast<std::size_t>(id)]);
    row["signature"] = signature;
    changed[static_cast<std::size_t>(id)] = row.dump();
    writeLines(jsonl, changed);
    const std::string msg = importError(dir.file("b.db"), {jsonl});
    CHECK(msg.find("line " + std::to_string(id + 1) + " (id " + std::to_string(id) + ").signature: ") != std::string::npos);
    CHECK(rowCount(dir.file("b.db")) == 0);
  }
}

TEST_CASE("verify names the rows whose signature does not parse or disagrees with the row") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db");
  fill(a, 4, 2);
  std::string arm_signature;
  {
    Connection c(a, OpenMode::ReadOnly);
    Statement get = c.prepare("SELECT signature FROM experiences WHERE id = 3");
    REQUIRE(get.step());
    arm_signature = get.textAt(0);
  }
  int n = 0;
  for (const auto& [id, signature] : badSignatures(arm_signature)) {
    CAPTURE(signature);
    const std::string copy = dir.file("bad-" + std::to_string(++n) + ".db");
    copyDatabase(a, copy);
    {
      Connection c(copy, OpenMode::ReadWrite);
      Statement put = c.prepare("UPDATE experiences SET signature = ?1 WHERE id = ?2");
      put.bind(1, std::string_view(signature)).bind(2, id);
      put.run();
    }
    VerifyReport r = verifyDatabase(copy);
    REQUIRE(r.problems.size() == 1);
    CHECK(r.problems[0].find("row " + std::to_string(id) + ": signature: ") != std::string::npos);
  }
}

// States no robot could take, in the middle of the rows fill() writes
// first (the start, goal, key and cost as they were): x = y = 1e300 for
// the mobile pair (id 1), joint 0 at 100 rad, far past its limits, for the
// arm pair (id 3). With `legal`, as far as each may go instead: x = y =
// 9e5, and joint 0 at its limit pi (which the signature rounds to 3.14159).
void farMiddleState(std::int64_t id, std::vector<std::vector<std::vector<double>>>& paths, bool legal = false) {
  auto& q = paths[0][paths[0].size() / 2];
  if (id == 1)
    q[0] = q[1] = legal ? 9e5 : 1e300;
  else
    q[0] = legal ? gen::kArmJoint1Limit : 100.0;
}

std::string farMiddleProblem(std::int64_t id, std::size_t states) {
  return "paths[0][" + std::to_string(states / 2) + "]: " +
         (id == 1 ? "x 1e+300 is beyond +-1e+06 of its subproblem's centre"
                   : "joint 0 100 is outside its limits -3.14159/3.14159");
}

TEST_CASE("an export row with a state its robot could not take is refused, naming the line and the state") {
  ScratchDirectory dir("transfer");
  const std::string jsonl = dir.file("a.jsonl");
  const auto lines = exportedLines(dir, jsonl, 4);
  for (bool legal : {false, true})
    for (std::int64_t id : {1, 3}) {
      CAPTURE(legal);
      CAPTURE(id);
      auto changed = lines;
      auto row = nlohmann::json::parse(changed[static_cast<std::size_t>(id)]);
      auto paths = row["paths"].get<std::vector<std::vector<std::vector<double>>>>();
      farMiddleState(id, paths, legal);
      row["paths"] = paths;
      changed[static_cast<std::size_t>(id)] = row.dump();
      writeLines(jsonl, changed);
      const std::string b = dir.file("b" + std::to_string(legal) + std::to_string(id) + ".db");
      if (legal) {
        ExperienceStore store(b);
        CHECK(importInto(store, {jsonl}).inserted == lines.size() - 1);
        continue;
      }
      const std::string msg = importError(b, {jsonl});
      CHECK(msg.find("line " + std::to_string(id + 1) + " (id " + std::to_string(id) +
                     "): " + farMiddleProblem(id, paths[0].size())) != std::string::npos);
      CHECK(msg.find("nothing was imported") != std::string::npos);
      CHECK(rowCount(b) == 0);
    }
}

TEST_CASE("a row with a state its robot could not take is refused on insert and listed by verify") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db");
  fill(a, 4, 2);
  // Written with SQL, as a damaged or hand-made file could hold them.
  std::map<std::int64_t, std::size_t> states;
  for (std::int64_t id : {1, 3}) {
    Connection c(a, OpenMode::ReadWrite);
    Statement get = c.prepare("SELECT paths FROM experiences WHERE id = ?1");
    get.bind(1, id);
    REQUIRE(get.step());
    std::vector<Path> paths = decodePaths(get.blobAt(0), id);
    get.reset();
    std::vector<std::vector<std::vector<double>>> raw;
    for (const Path& p : paths) {
      raw.emplace_back();
      for (std::size_t t = 0; t < p.size(); ++t) raw.back().emplace_back(p.at(t), p.at(t) + p.dim());
    }
    farMiddleState(id, raw);
    for (std::size_t r = 0; r < paths.size(); ++r) paths[r] = earc::test::line(raw[r]);
    states[id] = paths[0].size();
    Statement put = c.prepare("UPDATE experiences SET paths = ?1 WHERE id = ?2");
    put.bindBlob(1, encodePaths(paths)).bind(2, id);
    put.run();
  }
  VerifyReport r = verifyDatabase(a);
  CHECK_FALSE(r.ok());
  REQUIRE(r.problems.size() == 2);
  CHECK(r.problems[0].find("row 1: " + farMiddleProblem(1, states[1])) != std::string::npos);
  CHECK(r.problems[1].find("row 3: " + farMiddleProblem(3, states[3])) != std::string::npos);

  // An insert of such a row is refused, the file left as it was.
  std::mt19937_64 rng(4);
  const RobotTraits d = earc::test::discTraits();
  Experience bad = straightLineExperience(std::vector<RobotTraits>{d, d}, sampleMobileQuery(2, rng), 5);
  bad.paths[1].mutableAt(2)[1] = -2e6;
  ExperienceStore store(a);
  const std::size_t before = store.size();
  try {
    store.insert(bad, -1);
    FAIL("a row with y = -2e6 was inserted");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("paths[1][2]: y -2e+06 is beyond +-1e+06") != std::string::npos);
  }
  CHECK(store.size() == before);
}

TEST_CASE("an export row whose key disagrees with its paths is refused") {
  ScratchDirectory dir("transfer");
  const std::string jsonl = dir.file("a.jsonl");
  auto lines = exportedLines(dir, jsonl, 4);
  auto row = nlohmann::json::parse(lines[1]);
  row["key"][0] = row["key"][0].get<double>() + 1.0;
  lines[1] = row.dump();
  writeLines(jsonl, lines);
  CHECK(importError(dir.file("b.db"), {jsonl}).find("disagrees with the paths") != std::string::npos);
}

TEST_CASE("a truncated export is refused by its announced row count") {
  ScratchDirectory dir("transfer");
  const std::string jsonl = dir.file("a.jsonl");
  auto lines = exportedLines(dir, jsonl, 5);
  lines.pop_back();
  writeLines(jsonl, lines);
  CHECK(importError(dir.file("b.db"), {jsonl}).find("truncated") != std::string::npos);
}

TEST_CASE("an export from a newer schema, or with a header count that is no count, is refused") {
  ScratchDirectory dir("transfer");
  const std::string jsonl = dir.file("a.jsonl");
  const auto lines = exportedLines(dir, jsonl, 5);
  auto withHeader = [&](const char* key, const nlohmann::json& value) {
    auto changed = lines;
    auto header = nlohmann::json::parse(changed[0]);
    header[key] = value;
    changed[0] = header.dump();
    writeLines(jsonl, changed);
    return importError(dir.file("b.db"), {jsonl});
  };
  CHECK(withHeader("schema_version", 99).find("newer than this program's version") != std::string::npos);
  CHECK(withHeader("schema_version", "3").find("schema_version must be a positive integer") != std::string::npos);
  CHECK(withHeader("rows", "10").find("rows must be a count of rows") != std::string::npos);
  writeLines(jsonl, lines);  // the header as written imports
  ExperienceStore b(dir.file("b.db"));
  CHECK(importInto(b, {jsonl}).inserted == static_cast<std::size_t>(nlohmann::json::parse(lines[0])["rows"].get<int>()));
}

TEST_CASE("a database with a corrupt blob is refused as an import source, naming the row id") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db"), b = dir.file("b.db");
  fill(a, 6);
  {
    Connection c(a, OpenMode::ReadWrite);
    c.exec("UPDATE experiences SET paths = substr(paths, 1, length(paths) - 8) WHERE id = 17");
  }
  const std::string msg = importError(b, {a});
  CHECK(msg.find("row 17") != std::string::npos);
  CHECK(msg.find("length") != std::string::npos);
  CHECK(rowCount(b) == 0);
}

TEST_CASE("a foreign SQLite file is refused as an import source") {
  ScratchDirectory dir("transfer");
  const std::string foreign = dir.file("foreign.db");
  {
    Connection c(foreign, OpenMode::ReadWrite);
    c.exec("CREATE TABLE experiences (id INTEGER PRIMARY KEY, kind TEXT)");
  }
  CHECK(importError(dir.file("b.db"), {foreign}).find("not an earc experience database") != std::string::npos);
}

TEST_CASE("verify passes a sound database and names every bad row of a damaged one") {
  ScratchDirectory dir("transfer");
  const std::string a = dir.file("a.db");
  fill(a, 7);
  VerifyReport ok = verifyDatabase(a);
  CHECK(ok.ok());
  CHECK(ok.rows == 60);
  {
    Connection c(a, OpenMode::ReadWrite);
    Statement get = c.prepare("SELECT paths FROM experiences WHERE id = 4");
    REQUIRE(get.step());
    auto blob = std::vector<unsigned char>(get.blobAt(0).begin(), get.blobAt(0).end());
    get.reset();
    blob[4] = 4;  // format version 4
    Statement put = c.prepare("UPDATE experiences SET paths = ?1 WHERE id = 4");
    put.bindBlob(1, blob);
    put.run();
    c.exec("UPDATE experiences SET key = substr(key, 1, 8) WHERE id = 9");
  }
  VerifyReport bad = verifyDatabase(a);
  CHECK_FALSE(bad.ok());
  REQUIRE(bad.problems.size() == 2);
  CHECK(bad.problems[0].find("row 4: path blob: format version 4") != std::string::npos);
  CHECK(bad.problems[1].find("row 9: key has 1 values") != std::string::npos);
}
