// Whole experience rows in the PostgreSQL store: the same checks as
// rows.cpp's SQLite reader (kind and source names, blob headers and
// lengths, findProblem), on a binary result.
#include "earc/experience/path_blob.hpp"
#include "earc/experience/pg_schema.hpp"

namespace earc::exp {

namespace {

enum PgColumn {
  kPgId, kPgKind, kPgRobotCount, kPgSignature, kPgBaseClass, kPgKey, kPgPaths, kPgCost, kPgSource, kPgCreatedAt,
  kPgSolveTime, kPgRetrieved, kPgSucceeded, kPgCreatedSession, kPgMadeBy
};

}  // namespace

constexpr const char* kPgColumnList =
    "id, kind, robot_count, signature, base_class, key, paths, cost, source, created_at, solve_time_s, "
    "retrieved_count, succeeded_count, created_session, made_by";

std::string pgSelectExperiencesSql() { return std::string("SELECT ") + kPgColumnList + " FROM earc.experiences"; }

std::string pgSelectTailWithDeletionsSql() {
  return std::string("SELECT ") + kPgColumnList +
         ", d.value FROM (SELECT value FROM earc.store_meta WHERE name = 'deletions') d "
         "LEFT JOIN earc.experiences e ON e.id > $1 ORDER BY e.id";
}

Experience readPgExperience(const PgResult& r, int row) {
  Experience e;
  e.id = r.int64At(row, kPgId);
  const std::string kind_text = r.textAt(row, kPgKind);
  auto kind = kindFromName(kind_text);
  if (!kind) throw CorruptRowError(e.id, "unknown kind \"" + kind_text + "\"");
  const std::string source_text = r.textAt(row, kPgSource);
  auto source = sourceFromName(source_text);
  if (!source) throw CorruptRowError(e.id, "unknown source \"" + source_text + "\"");
  const std::int64_t count = r.int64At(row, kPgRobotCount);
  if (count < 1 || count > kMaxBlobRobots)
    throw CorruptRowError(e.id, "robot_count " + std::to_string(count) + " out of range");
  e.cls = {*kind, static_cast<int>(count), r.textAt(row, kPgSignature), r.textAt(row, kPgBaseClass)};
  e.key = decodeKey(r.bytesAt(row, kPgKey), e.id);
  e.paths = decodePaths(r.bytesAt(row, kPgPaths), e.id);
  e.cost = r.doubleAt(row, kPgCost);
  e.source = *source;
  e.created_at = r.int64At(row, kPgCreatedAt);
  e.solve_time_s = r.doubleAt(row, kPgSolveTime);
  e.retrieved = r.int64At(row, kPgRetrieved);
  e.succeeded = r.int64At(row, kPgSucceeded);
  e.created_session = r.int64At(row, kPgCreatedSession);
  e.made_by = r.textAt(row, kPgMadeBy);
  if (auto problem = findProblem(e)) throw CorruptRowError(e.id, *problem);
  return e;
}

std::string pgInsertExperiencesSql(std::size_t rows) {
  std::string sql =
      "INSERT INTO earc.experiences (kind, robot_count, signature, base_class, key, paths, cost, source, "
      "created_at, solve_time_s, retrieved_count, succeeded_count, created_session, made_by) VALUES ";
  int param = 1;
  for (std::size_t r = 0; r < rows; ++r) {
    sql += r ? ", (" : "(";
    for (int c = 0; c < kPgInsertColumns; ++c) sql += (c ? ", $" : "$") + std::to_string(param++);
    sql += ")";
  }
  return sql + " RETURNING id";
}

PgParams pgExperienceParams(const Experience& e) {
  PgParams p;
  p.add(kindName(e.cls.kind))
      .add(e.cls.robot_count)
      .add(std::string_view(e.cls.signature))
      .add(std::string_view(e.cls.base_class))
      .addBytes(encodeKey(e.key))
      .addBytes(encodePaths(e.paths))
      .add(e.cost)
      .add(sourceName(e.source))
      .add(e.created_at)
      .add(e.solve_time_s)
      .add(e.retrieved)
      .add(e.succeeded)
      .add(e.created_session)
      .add(std::string_view(e.made_by));
  return p;
}

void pgForEachExperience(PgConnection& db, const std::string& order, const std::function<void(std::int64_t)>& onCount,
                         const std::function<void(Experience&&)>& onRow,
                         const std::function<void(const CorruptRowError&)>& onDamaged) {
  db.exec("BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY");
  try {
    if (onCount) onCount(db.query("SELECT count(*) FROM earc.experiences").int64At(0, 0));
    // A BINARY cursor: its rows come as query()'s do.
    db.exec("DECLARE earc_rows BINARY NO SCROLL CURSOR FOR " + pgSelectExperiencesSql() + " " + order);
    for (;;) {
      PgResult r = db.exec("FETCH 1000 FROM earc_rows");
      for (int i = 0; i < r.rows(); ++i) {
        try {
          onRow(readPgExperience(r, i));
        } catch (const CorruptRowError& e) {
          if (!onDamaged) throw;
          onDamaged(e);
        }
      }
      if (r.rows() < 1000) break;
    }
    db.exec("COMMIT");
  } catch (...) {
    if (db.inTransaction()) {
      try {
        db.exec("ROLLBACK");
      } catch (const StoreError&) {
        // the connection is gone: so is the transaction
      }
    }
    throw;
  }
}

}  // namespace earc::exp
