#include "json_reader.hpp"

#include <errno.h>  // program_invocation_short_name

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <iterator>

#include "earc/io/json_io.hpp"

namespace earc {

std::string inputWarningLine(const InputWarning& warning, std::string_view program) {
  return std::string(program) + ": warning: " + printableText(warning.text(), 4096);
}

void printInputWarnings(const InputWarnings& warnings) {
  // The name the program was started by (glibc's): earc-plan, earc-db,
  // earc-bench, as their errors say.
  for (const InputWarning& w : warnings) std::cerr << inputWarningLine(w, program_invocation_short_name) << "\n";
}

}  // namespace earc

namespace earc::io {

void deliverWarnings(std::vector<InputWarning>&& found, std::vector<InputWarning>* sink) {
  if (sink == nullptr) printInputWarnings(found);
  else sink->insert(sink->end(), std::make_move_iterator(found.begin()), std::make_move_iterator(found.end()));
}

std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case json::value_t::string: {
      std::string s = v.get<std::string>();
      if (s.size() > 40) s = s.substr(0, 37) + "...";
      return "the string \"" + s + "\"";
    }
    case json::value_t::array: return "an array of " + std::to_string(v.size());
    case json::value_t::object: return "an object";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float: return "the number " + formatNumber(v.get<double>());
    default: return "a value of another kind";
  }
}

void JsonReader::fail(const std::string& path, const std::string& reason) const {
  throw InputError(file_, path, reason);
}

const json& JsonReader::object(const json& v, const std::string& path) const {
  if (!v.is_object()) fail(path, "expected an object, got " + describe(v));
  return v;
}

const json& JsonReader::array(const json& v, const std::string& path) const {
  if (!v.is_array()) fail(path, "expected an array, got " + describe(v));
  return v;
}

namespace {

// Edit distance with adjacent transpositions (optimal string alignment),
// ignoring case: "gaol" and "Goal" are both one edit from "goal".
std::size_t editDistance(const std::string& a, const std::string& b) {
  auto lower = [](char c) { return std::tolower(static_cast<unsigned char>(c)); };
  const std::size_t m = b.size();
  // Rows i-2, i-1 and i of the table.
  std::vector<std::size_t> before(m + 1), last(m + 1), row(m + 1);
  for (std::size_t j = 0; j <= m; ++j) last[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      row[j] = std::min({last[j] + 1, row[j - 1] + 1, last[j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
        row[j] = std::min(row[j], before[j - 2] + 1);
    }
    std::swap(before, last);
    std::swap(last, row);
  }
  return last[m];
}

// How many edits still make a near miss of `word`: one for short words
// ("min" and "max" are two apart), two from five letters on. The
// contract's keys of one object are further apart than that.
std::size_t nearMissEdits(const std::string& word) { return word.size() < 5 ? 1 : 2; }

}  // namespace

const char* nearMiss(const std::string& key, std::initializer_list<const char*> candidates) {
  const char* best = nullptr;
  std::size_t best_edits = 0;
  for (const char* c : candidates) {
    // Lengths further apart than the edits allowed: no near miss (and a
    // long key costs nothing).
    const std::size_t length = std::strlen(c);
    if (std::max(key.size(), length) - std::min(key.size(), length) > nearMissEdits(c)) continue;
    const std::size_t edits = editDistance(key, c);
    if (edits <= nearMissEdits(c) && (best == nullptr || edits < best_edits)) best = c, best_edits = edits;
  }
  return best;
}

void JsonReader::warn(const std::string& path, const std::string& reason) const {
  if (warnings_ == nullptr) return;
  if (warnings_->size() < kMostWarnings) warnings_->push_back({file_, path, reason});
  else ++unsaid_;
}

void JsonReader::deliverWarnings(std::vector<InputWarning>* sink) const {
  if (warnings_ == nullptr) return;
  if (unsaid_ > 0) warnings_->push_back({file_, "", std::to_string(unsaid_) + " more warnings like these, not shown"});
  io::deliverWarnings(std::move(*warnings_), sink);
}

void JsonReader::unknownKeys(const json& obj, const std::string& path, std::initializer_list<const char*> known,
                             std::initializer_list<OtherKindKey> others, const char* kind) const {
  for (const auto& [key, value] : obj.items()) {
    if (std::any_of(known.begin(), known.end(), [&](const char* k) { return key == k; })) continue;
    const std::string where = member(path, key.c_str());
    const auto other = std::find_if(others.begin(), others.end(), [&](const OtherKindKey& o) { return key == o.key; });
    if (other != others.end()) {
      warn(where, std::string(other->owner) + " key, ignored on " + kind);
      continue;
    }
    const char* near = nearMiss(key, known);
    warn(where, "unknown key, ignored" + (near ? " (did you mean \"" + std::string(near) + "\"?)" : std::string()));
  }
}

const json& JsonReader::required(const json& obj, const char* key, const std::string& path) const {
  auto it = obj.find(key);
  if (it == obj.end()) {
    std::string found;
    if (obj.is_object())
      for (const auto& [k, v] : obj.items())
        if (nearMiss(k, {key})) {
          found = " (found \"" + k + "\")";
          break;
        }
    fail(member(path, key), "missing required field \"" + std::string(key) + "\"" + found);
  }
  return *it;
}

const json* JsonReader::optional(const json& obj, const char* key, bool null_is_absent) const {
  auto it = obj.find(key);
  if (it == obj.end() || (null_is_absent && it->is_null())) return nullptr;
  return &*it;
}

std::string JsonReader::string(const json& v, const std::string& path) const {
  if (!v.is_string()) fail(path, "expected a string, got " + describe(v));
  return v.get<std::string>();
}

bool JsonReader::boolean(const json& v, const std::string& path) const {
  if (!v.is_boolean()) fail(path, "expected true or false, got " + describe(v));
  return v.get<bool>();
}

double JsonReader::number(const json& v, const std::string& path) const {
  if (!v.is_number()) fail(path, "expected a number, got " + describe(v));
  const double d = v.get<double>();
  // The parser refuses NaN, Infinity and overflowing literals; a document
  // built in memory may still hold them.
  if (!std::isfinite(d)) fail(path, "not a finite number");
  return d;
}

double JsonReader::positive(const json& v, const std::string& path) const {
  const double d = number(v, path);
  if (!(d > 0.0)) fail(path, "must be > 0, got " + formatNumber(d));
  return d;
}

double JsonReader::nonNegative(const json& v, const std::string& path) const {
  const double d = number(v, path);
  if (!(d >= 0.0)) fail(path, "must be >= 0, got " + formatNumber(d));
  return d;
}

std::vector<double> JsonReader::numbers(const json& v, std::size_t n, const std::string& path,
                                        const char* what) const {
  const std::string expected = "expected an array of " + std::to_string(n) + " numbers" +
                               (*what ? std::string(" (") + what + ")" : std::string());
  if (!v.is_array()) fail(path, expected + ", got " + describe(v));
  if (v.size() != n) fail(path, expected + ", got " + std::to_string(v.size()));
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = number(v[i], element(path, i));
  return out;
}

geo::Vec2 JsonReader::vec2(const json& v, const std::string& path) const {
  const auto xy = numbers(v, 2, path);
  return {xy[0], xy[1]};
}

void JsonReader::format(const json& doc, const char* expected) const {
  const json& f = required(doc, "format", "$");
  if (!f.is_string() || f.get<std::string>() != expected)
    fail("$.format", "expected \"" + std::string(expected) + "\", got " + describe(f));
}

}  // namespace earc::io
