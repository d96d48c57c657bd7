#include "json_reader.hpp"

#include <cmath>
#include <cstdio>

namespace earc::io {

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

const json& JsonReader::required(const json& obj, const char* key, const std::string& path) const {
  auto it = obj.find(key);
  if (it == obj.end()) fail(member(path, key), "missing required field \"" + std::string(key) + "\"");
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
