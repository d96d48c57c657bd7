// Whole experience rows in the PostgreSQL store: the same checks as
// rows.cpp's SQLite reader (kind and source names, blob headers and
// lengths, findProblem: decodeRowColumns), on a binary result.
#include "earc/experience/path_blob.hpp"
#include "earc/experience/pg_schema.hpp"
#include "row_columns.hpp"

namespace earc::exp {

constexpr const char* kPgColumnList =
    "id, kind, robot_count, signature, base_class, key, paths, cost, source, created_at, solve_time_s, "
    "retrieved_count, succeeded_count, created_session, made_by";

std::string pgSelectExperiencesSql() { return std::string("SELECT ") + kPgColumnList + " FROM earc.experiences"; }

std::string pgSelectTailWithDeletionsSql() {
  return std::string("SELECT ") + kPgColumnList +
         ", d.value FROM (SELECT value FROM earc.store_meta WHERE name = 'deletions') d "
         "LEFT JOIN earc.experiences e ON e.id > $1 ORDER BY e.id";
}

namespace {

// A result's row, for decodeRowColumns.
struct PgResultRowView {
  const PgResult& r;
  int row;
  std::int64_t int64(int c) const { return r.int64At(row, c); }
  double real(int c) const { return r.doubleAt(row, c); }
  std::string text(int c) const { return r.textAt(row, c); }
  std::span<const unsigned char> bytes(int c) const { return r.bytesAt(row, c); }
};

}  // namespace

Experience readPgExperience(const PgResult& r, int row) { return decodeRowColumns(PgResultRowView{r, row}); }

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
