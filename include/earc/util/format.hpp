// Text in messages and input: numbers in messages with six significant
// digits, never hundreds of digits (a 1e308 read from a file prints as
// 1e+308); whole numbers in input written as bare digits; one line of text
// out of anything.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <string>
#include <string_view>

namespace earc {

inline std::string formatNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// The same in a printf format of one number ("%.3f").
inline std::string formatNumber(const char* printf_format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, v);
  return buf;
}

// The shortest text that reads back as the same double ("10", "0.5",
// "1e-07", "1.0000001"): for numbers another program must read.
std::string exactNumber(double v);

// Whether `text` is one or more decimal digits and nothing else: no sign,
// space or point (a "-1" given to an unsigned option, a PID in a name).
inline bool isDigits(std::string_view text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](unsigned char c) { return c >= '0' && c <= '9'; });
}

// `text` on one line: line breaks become spaces. For text from elsewhere
// (SQLite's messages quote a damaged schema's SQL) in an error, a log line
// or a one-line reply.
inline std::string oneLine(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

// "2026-11-24T01:02:03Z" (UTC, ISO 8601) for Unix seconds.
inline std::string utcTimeText(std::int64_t unix_seconds) {
  const std::time_t t = static_cast<std::time_t>(unix_seconds);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// `text` as printable, valid UTF-8 on one line (control characters and
// bad bytes as '?'), cut at `max_bytes` (ending in "...").
std::string printableText(std::string_view text, std::size_t max_bytes);

// `text` as well-formed XML 1.0 character data and attribute value: & < > " '
// as entities, what XML 1.0 forbids and bad bytes as U+FFFD.
std::string xmlText(std::string_view text);

}  // namespace earc
