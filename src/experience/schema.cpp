#include "earc/experience/schema.hpp"

namespace earc::exp {

namespace {

// The tables each schema version has.
constexpr TableSince kTables[] = {{"experiences", 1}, {"store_meta", 2}};

}  // namespace

int checkIdentity(Connection& db) {
  return checkFileIdentity(db, {kApplicationId, "earc experience database", "earc", currentSchemaVersion(), kTables});
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
