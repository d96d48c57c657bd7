// Typed access to a parsed JSON document for the readers in src/io/: every
// accessor takes the value's JSON path ("$.robots[2].shape.radius") and
// throws InputError naming the file, that path and what is wrong.
#pragma once

#include <nlohmann/json.hpp>
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

class JsonReader {
 public:
  explicit JsonReader(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const std::string& path, const std::string& reason) const;

  const json& object(const json& v, const std::string& path) const;
  const json& array(const json& v, const std::string& path) const;
  // The member `key` of object obj (at path); missing is an error.
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
};

}  // namespace earc::io
