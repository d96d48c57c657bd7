// Rows of a results database read back, every value checked against what a
// run writes (results_rows.cpp). Internal to src/bench.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "earc/bench/options.hpp"
#include "earc/bench/results_db.hpp"
#include "earc/bench/suites.hpp"
#include "earc/experience/sqlite.hpp"
#include "earc/io/input_error.hpp"
#include "earc/util/format.hpp"

namespace earc::bench::results_detail {

using exp::Statement;

inline constexpr std::int64_t kNoCountLimit = std::numeric_limits<std::int64_t>::max();

// A value of a results row as a message shows it: 12, 1.5, inf, 'text'
// (cut short, on one line), NULL, a blob.
std::string resultValueText(const Statement& s, int c);

// "2026-11-24T01:02:03Z", as utcNow() writes it.
bool isUtcTimeText(std::string_view t);

// One row of a results table as read back, each value checked against what
// addTrial and addDatabase write: InputError naming file, table, row id
// (column 0) and column. Columns an older schema lacks read as optional.
class CheckedResultRow {
 public:
  CheckedResultRow(const Statement& s, const std::string& path, std::string_view table)
      : s_(s), path_(path), table_(table), id_(s.int64At(0)) {}

  [[noreturn]] void bad(int c, const std::string& reason) const {
    throw InputError(path_, std::string(table_) + " row id " + std::to_string(id_) + ", column " +
                                s_.columnName(c),
                     reason);
  }
  bool isNull(int c) const { return s_.columnType(c) == SQLITE_NULL; }
  std::string value(int c) const { return resultValueText(s_, c); }

  // An INTEGER from lo to most; `what` is what it must be ("a robot count
  // from 2 to 128").
  std::int64_t integer(int c, std::int64_t lo, std::int64_t most, std::string_view what) const {
    // The type first: after a conversion (int64At of a TEXT value) SQLite
    // no longer says what the value was.
    if (s_.columnType(c) != SQLITE_INTEGER || s_.int64At(c) < lo || s_.int64At(c) > most)
      bad(c, value(c) + " is not " + std::string(what));
    return s_.int64At(c);
  }
  std::optional<std::int64_t> optInteger(int c, std::int64_t lo, std::int64_t most, std::string_view what) const {
    if (isNull(c)) return std::nullopt;
    return integer(c, lo, most, what);
  }
  std::optional<std::int64_t> optCount(int c) const { return optInteger(c, 0, kNoCountLimit, "a count (0 or more)"); }
  // Seconds: a finite REAL (or a whole number SQLite stored as INTEGER),
  // 0 or more, above 0 where `positive`.
  double seconds(int c, bool positive = false) const {
    const int type = s_.columnType(c);
    const bool number = type == SQLITE_FLOAT || type == SQLITE_INTEGER;
    if (!number || !std::isfinite(s_.doubleAt(c)) || s_.doubleAt(c) < 0 || (positive && s_.doubleAt(c) == 0))
      bad(c, value(c) + " is not a number of seconds" + (positive ? " above 0" : " (0 or more)"));
    return s_.doubleAt(c);
  }
  std::optional<double> optSeconds(int c) const {
    if (isNull(c)) return std::nullopt;
    return seconds(c);
  }
  std::string text(int c) const {
    if (s_.columnType(c) != SQLITE_TEXT) bad(c, value(c) + " is not text");
    return s_.textAt(c);
  }
  // TEXT or NULL; NULL reads as "".
  std::string optText(int c) const { return isNull(c) ? std::string() : text(c); }
  // One of `names`, which the message lists.
  std::string oneOf(int c, const std::vector<std::string>& names, const char* what) const {
    const std::string v = text(c);
    if (std::find(names.begin(), names.end(), v) == names.end()) {
      std::string list;
      for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
      bad(c, value(c) + " is not " + what + " (" + list + ")");
    }
    return v;
  }
  // A seed as addTrial writes it: std::to_string of a 64-bit unsigned number.
  std::uint64_t seed(int c) const {
    std::uint64_t v = 0;
    const std::string t = s_.columnType(c) == SQLITE_TEXT ? s_.textAt(c) : std::string();
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || ec != std::errc() || end != t.data() + t.size() || std::to_string(v) != t)
      bad(c, value(c) + " is not a seed (a whole number from 0 to 2^64-1 as decimal text)");
    return v;
  }
  // NULL (none), or a JSON array of the arguments, as addTrial writes
  // them: at least one, each a string plannerArgsProblem accepts.
  std::vector<std::string> plannerArgs(int c) const {
    if (isNull(c)) return {};
    const std::string t = text(c);
    std::vector<std::string> args;
    const nlohmann::json j = nlohmann::json::parse(t, nullptr, /*allow_exceptions=*/false);
    const bool strings = j.is_array() && !j.empty() &&
                         std::all_of(j.begin(), j.end(), [](const nlohmann::json& a) { return a.is_string(); });
    if (!strings) bad(c, value(c) + " is not a JSON array of planner arguments (strings)");
    for (const auto& a : j) args.push_back(a.get<std::string>());
    if (const auto why = plannerArgsProblem(args)) bad(c, value(c) + " is not what a run gives a planner: " + *why);
    return args;
  }
  std::string utcTime(int c) const {
    if (s_.columnType(c) != SQLITE_TEXT || !isUtcTimeText(s_.textAt(c)))
      bad(c, value(c) + " is not a UTC time like 2026-11-24T01:02:03Z");
    return s_.textAt(c);
  }

 private:
  const Statement& s_;
  const std::string& path_;
  std::string_view table_;
  std::int64_t id_;
};

// The trial column of a Lightning option.
int lightningColumn(const std::string& option);

// A trials row (selectTrials' columns) and a databases row, checked.
TrialRecord readTrialRow(const CheckedResultRow& r);
DatabaseRecord readDatabaseRow(const CheckedResultRow& r);

}  // namespace earc::bench::results_detail
