// The experience database's history (schema 5 on): a line when the file
// is created or migrated, and one per open that then added or removed rows
// (built, imported, curated, learned while planning), saying which earc
// build did it, when, and how many rows it added and removed. Usage
// counters and the session count are not in it.
//
// A line is written with its open's first change, inside that change's
// transaction, and brought up to date inside each later one: after a crash
// at any point the history counts exactly the committed rows. A line is
// found again by a random token of its open, not by an id remembered from
// a transaction that may have rolled back.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "earc/experience/sqlite.hpp"

namespace earc::exp {

// The schema version that added the history table.
inline constexpr int kHistorySchemaVersion = 5;

// The longest detail kept (longer ones are cut, marked with "..."; control
// characters and bytes that are not UTF-8 become '?').
inline constexpr std::size_t kMaxHistoryDetail = 500;

// What one open does to a file: its line in the history.
class HistoryWriter {
 public:
  // operation: one of create, migrate, build, import, curate, learn.
  explicit HistoryWriter(std::string operation = "learn", std::string detail = {});
  void describe(std::string operation, std::string detail);

  // Inside a write transaction (schema >= 5; older: nothing): counts rows
  // on this open's line, written at the first change; zero counts write
  // nothing unless even_if_unchanged. describe() is ignored once written.
  void record(Connection& db, int schema_version, std::int64_t added, std::int64_t removed,
              bool even_if_unchanged = false) const;

  // This open's random token, operation and detail (the PostgreSQL store
  // writes the same line through its own connection).
  std::int64_t token() const { return token_; }
  const std::string& operation() const { return operation_; }
  const std::string& detail() const { return detail_; }

 private:
  std::int64_t token_;
  std::string operation_;
  std::string detail_;
};

struct HistoryLine {
  std::int64_t id = 0;
  std::int64_t at = 0;
  std::string program;
  std::string operation;
  std::string detail;
  std::int64_t rows_added = 0;
  std::int64_t rows_removed = 0;
  // Its open's random token: no other line of any file has it, and a copy
  // of the file keeps it, so the last line's says which file this is and
  // how far its changes go (earc-bench run holds a resumed run to it).
  std::int64_t token = 0;
};

// The last `limit` lines, oldest first, and how many lines there are in
// all. A file before schema 5 has none.
struct HistoryTail {
  std::vector<HistoryLine> lines;
  std::int64_t total = 0;
};
HistoryTail readHistory(Connection& db, int schema_version, int limit);

}  // namespace earc::exp
