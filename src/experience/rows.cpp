#include "earc/experience/rows.hpp"

#include "earc/experience/path_blob.hpp"
#include "row_columns.hpp"

namespace earc::exp {

namespace {

enum Column {
  kId, kKind, kRobotCount, kSignature, kBaseClass, kKey, kPaths, kCost, kSource, kCreatedAt,
  kSolveTime, kRetrieved, kSucceeded, kCreatedSession, kMadeBy
};

const char* typeName(int t) {
  switch (t) {
    case SQLITE_INTEGER: return "integer";
    case SQLITE_FLOAT: return "real";
    case SQLITE_TEXT: return "text";
    case SQLITE_BLOB: return "blob";
    default: return "null";
  }
}

void expectType(const Statement& s, std::int64_t row, int col, int type, const char* name) {
  int t = s.columnType(col);
  // A REAL column may hand back an integer-valued number stored compactly.
  if (t == type || (type == SQLITE_FLOAT && t == SQLITE_INTEGER)) return;
  throw CorruptRowError(row, std::string(name) + " is " + typeName(t) + ", expected " + typeName(type));
}

// A statement's row, for decodeRowColumns.
struct SqliteRowView {
  const Statement& s;
  std::int64_t int64(int c) const { return s.int64At(c); }
  double real(int c) const { return s.doubleAt(c); }
  std::string text(int c) const { return s.textAt(c); }
  std::span<const unsigned char> bytes(int c) const { return s.blobAt(c); }
};

}  // namespace

std::string selectExperiencesSql(int schema_version) {
  std::string cols = "id, kind, robot_count, signature, base_class, key, paths, cost, source, created_at, ";
  cols += schema_version >= 2 ? "solve_time_s, retrieved_count, succeeded_count, created_session"
                              : "0.0, 0, 0, 0";
  cols += schema_version >= 4 ? ", made_by" : ", ''";
  return "SELECT " + cols + " FROM experiences";
}

Experience readExperience(const Statement& s) {
  if (s.columnType(kId) != SQLITE_INTEGER) throw CorruptRowError(0, "id is not an integer");
  Experience e;
  e.id = s.int64At(kId);
  expectType(s, e.id, kKind, SQLITE_TEXT, "kind");
  expectType(s, e.id, kRobotCount, SQLITE_INTEGER, "robot_count");
  expectType(s, e.id, kSignature, SQLITE_TEXT, "signature");
  expectType(s, e.id, kBaseClass, SQLITE_TEXT, "base_class");
  expectType(s, e.id, kKey, SQLITE_BLOB, "key");
  expectType(s, e.id, kPaths, SQLITE_BLOB, "paths");
  expectType(s, e.id, kCost, SQLITE_FLOAT, "cost");
  expectType(s, e.id, kSource, SQLITE_TEXT, "source");
  expectType(s, e.id, kCreatedAt, SQLITE_INTEGER, "created_at");
  expectType(s, e.id, kSolveTime, SQLITE_FLOAT, "solve_time_s");
  expectType(s, e.id, kRetrieved, SQLITE_INTEGER, "retrieved_count");
  expectType(s, e.id, kSucceeded, SQLITE_INTEGER, "succeeded_count");
  expectType(s, e.id, kCreatedSession, SQLITE_INTEGER, "created_session");
  expectType(s, e.id, kMadeBy, SQLITE_TEXT, "made_by");
  return decodeRowColumns(SqliteRowView{s});
}

std::string insertExperienceSql() {
  return "INSERT INTO experiences (kind, robot_count, signature, base_class, key, paths, cost, source, created_at, "
         "solve_time_s, retrieved_count, succeeded_count, created_session, made_by) "
         "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14)";
}

void bindExperience(Statement& insert, const Experience& e) {
  insert.bind(1, std::string_view(kindName(e.cls.kind)))
      .bind(2, e.cls.robot_count)
      .bind(3, std::string_view(e.cls.signature))
      .bind(4, std::string_view(e.cls.base_class))
      .bindBlob(5, encodeKey(e.key))
      .bindBlob(6, encodePaths(e.paths))
      .bind(7, e.cost)
      .bind(8, std::string_view(sourceName(e.source)))
      .bind(9, e.created_at)
      .bind(10, e.solve_time_s)
      .bind(11, e.retrieved)
      .bind(12, e.succeeded)
      .bind(13, e.created_session)
      .bind(14, std::string_view(e.made_by));
}

}  // namespace earc::exp
