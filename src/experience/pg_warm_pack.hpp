// The compact form a PostgreSQL store's background copy keeps its rows in
// (PgWarmRows). Not a public header.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "earc/experience/experience.hpp"
#include "earc/experience/pg_connection.hpp"

namespace earc::exp {

// Numbers for the distinct strings of packed rows (signatures, base
// classes, builds), and those numbered since the last take. Not thread-safe.
class PgWarmStringNumbers {
 public:
  // The string's number: the next one when it is new.
  std::uint32_t of(std::string_view s);
  // The strings numbered since the last call, in number order.
  std::vector<std::string> takeAdded();

 private:
  std::unordered_map<std::string, std::uint32_t> numbers_;
  std::vector<std::string> added_;
};

// Appends row `row` of a result with pgSelectExperiencesSql's columns to
// `out`, packed (varints, numbered strings, key and cost as differences
// from the paths'). Throws StoreError for a NULL column.
void packPgWarmRow(const PgResult& r, int row, PgWarmStringNumbers& strings, std::vector<unsigned char>& out);
// The row with this id packed at `at`, decoded and checked as
// readPgExperience checks (strings[n] is string n). Throws CorruptRowError.
Experience unpackPgWarmRow(std::int64_t id, const unsigned char* at, const std::vector<std::string>& strings);

// The bytes a store of `rows` rows would take packed (with PgWarmRows's
// bookkeeping), estimated from a sample of its pages: never a whole-table
// read. 0 when the sample holds no row.
std::size_t estimatePgWarmBytes(PgConnection& pg, std::size_t rows);

}  // namespace earc::exp
