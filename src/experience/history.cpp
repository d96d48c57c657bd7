#include "earc/experience/history.hpp"

#include <ctime>
#include <random>

#include "earc/util/format.hpp"
#include "earc/util/version.hpp"

namespace earc::exp {

namespace {

std::int64_t randomToken() {
  std::random_device device;
  const std::uint64_t high = device(), low = device();
  return static_cast<std::int64_t>((high << 32) ^ low);
}

// Details come from command lines (file names, build names): kept
// printable and bounded, as shown.
std::string cleanDetail(std::string_view detail) { return printableText(detail, kMaxHistoryDetail); }

}  // namespace

HistoryWriter::HistoryWriter(std::string operation, std::string detail)
    : token_(randomToken()), operation_(std::move(operation)), detail_(cleanDetail(detail)) {}

void HistoryWriter::describe(std::string operation, std::string detail) {
  operation_ = std::move(operation);
  detail_ = cleanDetail(detail);
}

// even_if_unchanged: creating or migrating a file, a curate that removed
// nothing.
void HistoryWriter::record(Connection& db, int schema_version, std::int64_t added, std::int64_t removed,
                           bool even_if_unchanged) const {
  if (schema_version < kHistorySchemaVersion) return;
  if (added == 0 && removed == 0 && !even_if_unchanged) return;
  Statement update = db.prepare(
      "UPDATE history SET rows_added = rows_added + ?2, rows_removed = rows_removed + ?3 WHERE token = ?1");
  update.bind(1, token_).bind(2, added).bind(3, removed);
  update.run();
  if (sqlite3_changes(db.handle()) > 0) return;
  Statement insert = db.prepare(
      "INSERT INTO history (token, at, program, operation, detail, rows_added, rows_removed) "
      "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)");
  insert.bind(1, token_)
      .bind(2, static_cast<std::int64_t>(std::time(nullptr)))
      .bind(3, version())
      .bind(4, std::string_view(operation_))
      .bind(5, std::string_view(detail_))
      .bind(6, added)
      .bind(7, removed);
  insert.run();
}

HistoryTail readHistory(Connection& db, int schema_version, int limit) {
  HistoryTail tail;
  if (schema_version < kHistorySchemaVersion) return tail;
  Statement total = db.prepare("SELECT count(*) FROM history");
  if (total.step()) tail.total = total.int64At(0);
  Statement last = db.prepare(
      "SELECT id, at, program, operation, detail, rows_added, rows_removed, token FROM "
      "(SELECT * FROM history ORDER BY id DESC LIMIT ?1) ORDER BY id");
  last.bind(1, limit);
  while (last.step())
    tail.lines.push_back({last.int64At(0), last.int64At(1), last.textAt(2), last.textAt(3), last.textAt(4),
                          last.int64At(5), last.int64At(6), last.int64At(7)});
  return tail;
}

}  // namespace earc::exp
