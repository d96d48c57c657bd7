#include "earc/experience/schema.hpp"

#include <cstdio>
#include <filesystem>

namespace earc::exp {

namespace {

std::string hex32(std::int64_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%08llx", static_cast<unsigned long long>(v) & 0xffffffffull);
  return buf;
}

// The tables each schema version has (a migration adds, never drops one).
struct TableSince {
  const char* name;
  int version;
};
constexpr TableSince kTables[] = {{"experiences", 1}, {"store_meta", 2}};

// A table of the file's version that is not there means the file was
// damaged or edited: refused before any statement needs it (which would
// fail with SQL text, after the session count was already written).
void requireTables(Connection& db, int version) {
  Statement s = db.prepare("SELECT count(*) FROM sqlite_schema WHERE type = 'table' AND name = ?1");
  for (const TableSince& t : kTables) {
    if (t.version > version) continue;
    s.bind(1, std::string_view(t.name));
    s.step();
    const bool there = s.int64At(0) == 1;
    s.reset();
    if (!there)
      throw DamagedDatabaseError(db.path() + ": damaged database file (table " + t.name +
                                 " is missing; schema version " + std::to_string(version) + " has it)");
  }
}

}  // namespace

InputError notYetADatabase(const std::string& path) {
  std::error_code ec;
  const bool zero = std::filesystem::file_size(path, ec) == 0 && !ec;
  return InputError(path, "", zero ? "empty file (0 bytes), not an earc database yet"
                                   : "empty SQLite database (no tables), not an earc database yet");
}

void requireDatabaseFile(const std::string& path, bool may_be_empty) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw InputError(path, "", "no such file");
  if (fs::is_directory(st)) throw InputError(path, "", "is a directory, not a file");
  // SQLite reads a 0-byte file as an empty database; one whose pages are
  // all still in its WAL is not empty.
  if (!may_be_empty && fs::is_regular_file(st) && fs::file_size(path, ec) == 0 && !ec &&
      !(fs::file_size(path + "-wal", ec) > 0 && !ec))
    throw notYetADatabase(path);
}

int checkIdentity(Connection& db) {
  // One statement, one snapshot: another process may be creating the file
  // right now, and separate reads could mix its before and after.
  Statement s = db.prepare(
      "SELECT (SELECT application_id FROM pragma_application_id), (SELECT user_version FROM pragma_user_version), "
      "(SELECT count(*) FROM sqlite_schema)");
  s.step();  // NOTADB -> ForeignDatabaseError
  const std::int64_t app = s.int64At(0);
  const int version = static_cast<int>(s.int64At(1));
  const std::int64_t objects = s.int64At(2);
  s.reset();
  const int program = currentSchemaVersion();
  if (app == kApplicationId) {
    if (version > program)
      throw SchemaVersionError(db.path() + ": schema version " + std::to_string(version) +
                                   " is newer than this program's version " + std::to_string(program) +
                                   "; use a newer earc (this one would not understand the file)",
                               version, program);
    if (version < 1)
      throw ForeignDatabaseError(db.path() + ": earc application_id but schema version " +
                                 std::to_string(version) + "; the file was not created by earc");
    requireTables(db, version);
    return version;
  }
  if (app == 0 && version == 0 && objects == 0) return 0;  // empty or new file
  throw ForeignDatabaseError(db.path() + ": not an earc experience database (application_id " + hex32(app) +
                             ", expected " + hex32(kApplicationId) + " \"EARC\"; " + std::to_string(objects) +
                             " schema objects, user_version " + std::to_string(version) + ")");
}

int migrate(Connection& db, int target) {
  if (target < 0) target = currentSchemaVersion();
  const auto steps = migrations();
  for (;;) {
    // Each step re-reads the version inside its own write transaction, so
    // two processes opening a new file at once apply every step once.
    int reached = db.write([&]() -> int {
      int version = checkIdentity(db);
      if (version >= target) return version;
      const Migration& m = steps[static_cast<std::size_t>(version)];
      db.exec(m.sql);
      db.exec("PRAGMA user_version = " + std::to_string(m.version));
      return -1;
    });
    if (reached >= 0) return reached;
  }
}

}  // namespace earc::exp
