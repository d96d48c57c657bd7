// Typed access to a parsed JSON document for the readers in src/io/: every
// accessor takes the value's JSON path ("$.robots[2].shape.radius") and
// throws InputError naming the file, that path and what is wrong.
#pragma once

#include <nlohmann/json.hpp>
#include <initializer_list>
#include <string>
#include <vector>

#include "earc/geometry/shapes.hpp"
#include "earc/io/input_error.hpp"
#include "earc/util/format.hpp"

namespace earc::io {

using nlohmann::json;

// "$.robots" + "name" -> "$.robots.name"; "$.robots" + 2 -> "$.robots[2]".
inline std::string member(const std::string& path, const char* key) { return path + "." + key; }
inline std::string element(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

// Six significant digits of a number, for messages.
using earc::formatNumber;

// A short description of a JSON value's kind for "expected X, got Y".
std::string describe(const json& v);

// The key of `candidates` that `key` is most likely a misspelling of (a
// small edit distance, case, swapped neighbours and all: "angel" ->
// "angle", "translaton" -> "translation", "Goal" -> "goal"), or nullptr.
const char* nearMiss(const std::string& key, std::initializer_list<const char*> candidates);

// A key that belongs to another kind of the object being read: a mobile
// robot's "shape" on an arm is {"shape", "a mobile robot's"}.
struct OtherKindKey {
  const char* key;
  const char* owner;
};

// Warnings, once an input has been read whole: appended to `sink`, or
// printed (printInputWarnings) when there is none.
void deliverWarnings(std::vector<InputWarning>&& found, std::vector<InputWarning>* sink);

// Warnings kept of one file: a file of 200,000 obstacles with a stray key
// each would otherwise bury the terminal (and fill memory).
inline constexpr std::size_t kMostWarnings = 20;

class JsonReader {
 public:
  // Warnings go to `warnings` (which must outlive the reader); without it
  // they are dropped.
  explicit JsonReader(std::string file, std::vector<InputWarning>* warnings = nullptr)
      : file_(std::move(file)), warnings_(warnings) {}
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const std::string& path, const std::string& reason) const;
  // Input read all the same, but likely a mistake. Beyond kMostWarnings,
  // only counted.
  void warn(const std::string& path, const std::string& reason) const;
  // The warnings (and a line counting those beyond kMostWarnings) to
  // deliverWarnings, once the input has been read whole.
  void deliverWarnings(std::vector<InputWarning>* sink) const;
  // Warns of each key of obj (at path) not in `known`, lest a misspelt field
  // silently take its default: a key of `others` belongs to that other kind,
  // not this `kind` ("a manipulator"); a near miss of a known key is suggested.
  void unknownKeys(const json& obj, const std::string& path, std::initializer_list<const char*> known,
                   std::initializer_list<OtherKindKey> others = {}, const char* kind = "") const;

  const json& object(const json& v, const std::string& path) const;
  const json& array(const json& v, const std::string& path) const;
  // The member `key` of object obj (at path); missing is an error, which
  // names a key of obj that looks like a misspelling of it.
  const json& required(const json& obj, const char* key, const std::string& path) const;
  // The member `key`, or nullptr when absent (or null, when null_is_absent).
  const json* optional(const json& obj, const char* key, bool null_is_absent = false) const;

  std::string string(const json& v, const std::string& path) const;
  bool boolean(const json& v, const std::string& path) const;
  double number(const json& v, const std::string& path) const;
  double positive(const json& v, const std::string& path) const;     // > 0
  double nonNegative(const json& v, const std::string& path) const;  // >= 0
  // An array of exactly n numbers; `what` says why n in the message
  // ("one per link"), or is empty.
  std::vector<double> numbers(const json& v, std::size_t n, const std::string& path,
                              const char* what = "") const;
  geo::Vec2 vec2(const json& v, const std::string& path) const;
  // Checks doc["format"] == expected.
  void format(const json& doc, const char* expected) const;

 private:
  std::string file_;
  std::vector<InputWarning>* warnings_ = nullptr;
  mutable std::size_t unsaid_ = 0;  // warnings beyond kMostWarnings
};

}  // namespace earc::io
