// A packed row is a form byte, then either the compact fields
//   kind, source (a byte each), robot_count, signature, base class and
//   made_by (string numbers), created_at, retrieved, succeeded,
//   created_session (zigzag varints), solve_time_s (8 bytes), the cost's
//   and each key value's difference from pathCost and keyOfCanonicalPaths
//   of the paths (zigzag varints of the IEEE bit patterns' difference:
//   exact, one byte when they agree), the path blob's length and bytes;
// or, for a row that does not decode, every column's length and bytes as
// the server sent them. A decoded row is the one readPgExperience gives.
#include "pg_warm_pack.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "earc/experience/keys.hpp"
#include "earc/experience/path_blob.hpp"
#include "earc/experience/pg_schema.hpp"
#include "row_columns.hpp"

namespace earc::exp {

namespace {

enum PgWarmForm : unsigned char { kWarmColumns = 0, kWarmCompact = 1 };

// Bookkeeping per packed row: its slot in PgWarmRows's table (id, batch,
// offset) and the compact form's fields other than the key and paths.
constexpr std::size_t kWarmSlotBytes = 16, kWarmFieldBytes = 32;

void warmPutVarint(std::vector<unsigned char>& out, std::uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<unsigned char>((v & 0x7f) | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<unsigned char>(v));
}

std::uint64_t warmGetVarint(const unsigned char*& at) {
  std::uint64_t v = 0;
  for (int shift = 0;; shift += 7) {
    const unsigned char b = *at++;
    v |= static_cast<std::uint64_t>(b & 0x7f) << shift;
    if (!(b & 0x80)) return v;
  }
}

std::uint64_t warmZigzag(std::int64_t v) {
  return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63);
}
std::int64_t warmUnzigzag(std::uint64_t z) { return static_cast<std::int64_t>((z >> 1) ^ (~(z & 1) + 1)); }

// A double's difference from a reference, exact (bit patterns, zigzagged).
std::uint64_t warmDifference(double v, double reference) {
  return warmZigzag(static_cast<std::int64_t>(std::bit_cast<std::uint64_t>(v) - std::bit_cast<std::uint64_t>(reference)));
}
double warmFromDifference(std::uint64_t z, double reference) {
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(reference) + static_cast<std::uint64_t>(warmUnzigzag(z)));
}

void warmPutDouble(std::vector<unsigned char>& out, double v) {
  unsigned char b[8];
  std::memcpy(b, &v, 8);
  out.insert(out.end(), b, b + 8);
}
double warmGetDouble(const unsigned char*& at) {
  double v;
  std::memcpy(&v, at, 8);
  at += 8;
  return v;
}

// The columns of a row kept column by column, for decodeRowColumns.
struct PgWarmColumnsView {
  std::array<std::span<const unsigned char>, kPgRowColumns> cols;
  std::span<const unsigned char> bytes(int c) const { return cols[static_cast<std::size_t>(c)]; }
  std::int64_t int64(int c) const { return pgBinaryInt(bytes(c)); }
  double real(int c) const { return pgBinaryDouble(bytes(c)); }
  std::string text(int c) const { return std::string(bytes(c).begin(), bytes(c).end()); }
};

std::string_view pgWarmText(const PgResult& r, int row, int c) {
  const auto b = r.bytesAt(row, c);
  return {reinterpret_cast<const char*>(b.data()), b.size()};
}

// The compact form of the row, or false (out unchanged) when it would not
// decode: the column form keeps it then.
bool packCompactWarmRow(const PgResult& r, int row, PgWarmStringNumbers& strings, std::vector<unsigned char>& out) {
  const std::size_t start = out.size();
  try {
    const std::int64_t id = r.int64At(row, kColId);
    const auto kind = kindFromName(pgWarmText(r, row, kColKind));
    const auto source = sourceFromName(pgWarmText(r, row, kColSource));
    const std::int64_t count = r.int64At(row, kColRobotCount);
    if (!kind || !source || count < 1 || count > kMaxBlobRobots) return false;
    const std::vector<double> key = decodeKey(r.bytesAt(row, kColKey), id);
    const auto blob = r.bytesAt(row, kColPaths);
    const std::vector<Path> paths = decodePaths(blob, id);
    const std::vector<double> expected = keyOfCanonicalPaths(*kind, paths);
    if (key.size() != expected.size()) return false;
    out.push_back(kWarmCompact);
    out.push_back(static_cast<unsigned char>(*kind));
    out.push_back(static_cast<unsigned char>(*source));
    warmPutVarint(out, static_cast<std::uint64_t>(count));
    for (int c : {kColSignature, kColBaseClass, kColMadeBy}) warmPutVarint(out, strings.of(pgWarmText(r, row, c)));
    for (int c : {kColCreatedAt, kColRetrieved, kColSucceeded, kColCreatedSession})
      warmPutVarint(out, warmZigzag(r.int64At(row, c)));
    warmPutDouble(out, r.doubleAt(row, kColSolveTime));
    warmPutVarint(out, warmDifference(r.doubleAt(row, kColCost), pathCost(paths)));
    warmPutVarint(out, key.size());
    for (std::size_t i = 0; i < key.size(); ++i) warmPutVarint(out, warmDifference(key[i], expected[i]));
    warmPutVarint(out, blob.size());
    out.insert(out.end(), blob.begin(), blob.end());
    return true;
  } catch (const std::exception&) {
    out.resize(start);
    return false;
  }
}

}  // namespace

std::uint32_t PgWarmStringNumbers::of(std::string_view s) {
  auto [it, added] = numbers_.try_emplace(std::string(s), static_cast<std::uint32_t>(numbers_.size()));
  if (added) added_.emplace_back(s);
  return it->second;
}

std::vector<std::string> PgWarmStringNumbers::takeAdded() {
  std::vector<std::string> out;
  out.swap(added_);
  return out;
}

// The key and cost take a byte a value, usually; the path blob is kept as
// stored. A row that would not decode is kept column by column, so that it
// fails as readPgExperience fails.
void packPgWarmRow(const PgResult& r, int row, PgWarmStringNumbers& strings, std::vector<unsigned char>& out) {
  for (int c = 0; c < kPgRowColumns; ++c)
    if (r.isNull(row, c)) throw StoreError("row " + std::to_string(row) + " of the copy: column " + std::to_string(c) + " is NULL");
  if (packCompactWarmRow(r, row, strings, out)) return;
  out.push_back(kWarmColumns);
  for (int c = 0; c < kPgRowColumns; ++c) {
    const auto b = r.bytesAt(row, c);
    warmPutVarint(out, b.size());
    out.insert(out.end(), b.begin(), b.end());
  }
}

Experience unpackPgWarmRow(std::int64_t id, const unsigned char* at, const std::vector<std::string>& strings) {
  if (*at++ == kWarmColumns) {
    PgWarmColumnsView view;
    for (auto& col : view.cols) {
      const std::size_t n = warmGetVarint(at);
      col = {at, n};
      at += n;
    }
    return decodeRowColumns(view);
  }
  Experience e;
  e.id = id;
  e.cls.kind = static_cast<RobotKind>(*at++);
  e.source = static_cast<Source>(*at++);
  e.cls.robot_count = static_cast<int>(warmGetVarint(at));
  e.cls.signature = strings.at(warmGetVarint(at));
  e.cls.base_class = strings.at(warmGetVarint(at));
  e.made_by = strings.at(warmGetVarint(at));
  e.created_at = warmUnzigzag(warmGetVarint(at));
  e.retrieved = warmUnzigzag(warmGetVarint(at));
  e.succeeded = warmUnzigzag(warmGetVarint(at));
  e.created_session = warmUnzigzag(warmGetVarint(at));
  e.solve_time_s = warmGetDouble(at);
  const std::uint64_t cost = warmGetVarint(at);
  e.key.resize(warmGetVarint(at));
  std::vector<std::uint64_t> key_differences(e.key.size());
  for (std::uint64_t& d : key_differences) d = warmGetVarint(at);
  const std::size_t blob = warmGetVarint(at);
  e.paths = decodePaths({at, blob}, id);
  e.cost = warmFromDifference(cost, pathCost(e.paths));
  const std::vector<double> expected = keyOfCanonicalPaths(e.cls.kind, e.paths);
  for (std::size_t i = 0; i < e.key.size(); ++i) e.key[i] = warmFromDifference(key_differences[i], expected[i]);
  if (auto problem = findProblem(e)) throw CorruptRowError(id, *problem);
  return e;
}

std::size_t estimatePgWarmBytes(PgConnection& pg, std::size_t rows) {
  if (rows == 0) return 0;
  // About 2,000 rows' pages: a few milliseconds of the server's time.
  const double percent = std::min(100.0, 100.0 * 2000.0 / static_cast<double>(rows));
  char sql[256];
  std::snprintf(sql, sizeof sql,
                "SELECT count(*), coalesce(sum(octet_length(paths)), 0), coalesce(sum(octet_length(key)), 0) "
                "FROM earc.experiences TABLESAMPLE SYSTEM (%.6f)",
                percent);
  const PgResult r = pg.retryLost([&] { return pg.query(sql); });
  const std::int64_t sampled = r.int64At(0, 0);
  if (sampled <= 0) return 0;
  // A path blob's length varint (2 bytes) and a byte per key value.
  const double per_row = static_cast<double>(kWarmSlotBytes + kWarmFieldBytes + 2) +
                         static_cast<double>(r.int64At(0, 1) + r.int64At(0, 2) / 8) / static_cast<double>(sampled);
  return static_cast<std::size_t>(per_row * static_cast<double>(rows));
}

}  // namespace earc::exp
