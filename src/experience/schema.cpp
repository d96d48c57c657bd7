#include "earc/experience/schema.hpp"

#include <filesystem>

#include "earc/experience/history.hpp"

namespace earc::exp {

namespace {

// The tables each schema version has.
constexpr TableSince kTables[] = {{"experiences", 1}, {"store_meta", 2}, {"history", kHistorySchemaVersion}};

}  // namespace

// One wording wherever it is refused: "FILE: empty file (0 bytes), not an
// earc database yet". Commands that write a file make it a database.
InputError notYetADatabase(const std::string& path, std::string_view what) {
  std::error_code ec;
  const bool zero = std::filesystem::file_size(path, ec) == 0 && !ec;
  return InputError(path, "",
                    (zero ? "empty file (0 bytes), not " : "empty SQLite database (no tables), not ") +
                        std::string(what) + " yet");
}

void requireDatabaseFile(const std::string& path, bool may_be_empty) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw InputError(path, "", "no such file");
  if (fs::is_directory(st)) throw InputError(path, "", "is a directory, not a file");
  if (!fs::is_regular_file(st)) throw InputError(path, "", kNotARegularFile);
  // SQLite reads a 0-byte file as an empty database; one whose pages are
  // all still in its WAL is not empty. The WAL is the one SQLite reads:
  // beside a link's target, not beside the link.
  if (!may_be_empty && fs::is_regular_file(st) && fs::file_size(path, ec) == 0 && !ec &&
      !(fs::file_size(databaseFile(path) + "-wal", ec) > 0 && !ec))
    throw notYetADatabase(path);
}

int checkIdentity(Connection& db) {
  return checkFileIdentity(db, {kApplicationId, "earc experience database", "earc", currentSchemaVersion(), kTables});
}

// Each migration runs in a BEGIN IMMEDIATE transaction with its user_version
// bump, so a crash leaves the previous version intact; a new (empty) file
// gets every migration in one such transaction.
int migrate(Connection& db, int target) {
  if (target < 0) target = currentSchemaVersion();
  const auto steps = migrations();
  int from = -1;  // the version before this call's first step
  for (;;) {
    // Each step re-reads the version inside its own write transaction, so
    // two processes opening a new file at once apply every step once.
    int reached = db.write([&]() -> int {
      int version = checkIdentity(db);
      if (version >= target) return version;
      if (from < 0) from = version;
      // A new file is made whole in one transaction: it appears at the
      // target version or not at all, and its history's first line names
      // its creator (another process creating it at the same time finds it
      // done). An existing file moves one step per transaction.
      const bool creating = version == 0;
      do {
        const Migration& m = steps[static_cast<std::size_t>(version)];
        db.exec(m.sql);
        db.exec("PRAGMA user_version = " + std::to_string(m.version));
        version = m.version;
      } while (creating && version < target);
      // The last step says in the history who created or migrated the
      // file, in its own transaction: a crash before it leaves no line.
      // (Two programs migrating one older file at once: the line names the
      // one that took the last step, from the version it first found.)
      if (version == target) {
        const std::string to = "schema " + std::to_string(target);
        HistoryWriter(creating ? "create" : "migrate",
                      creating ? to : "schema " + std::to_string(from) + " to " + std::to_string(target))
            .record(db, version, 0, 0, true);
      }
      return -1;
    });
    if (reached >= 0) return reached;
  }
}

}  // namespace earc::exp
