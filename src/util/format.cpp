#include "earc/util/format.hpp"

#include <algorithm>
#include <charconv>
#include <vector>

namespace earc {

namespace {

// The length of the valid UTF-8 character at text[i], 0 when the bytes
// there are not one (a stray continuation byte, an overlong form, a
// surrogate, beyond U+10FFFF, cut short).
std::size_t utf8Length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b = byte(i);
  if (b < 0x80) return 1;
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // allowed range of the second byte
  if (b >= 0xC2 && b <= 0xDF) {
    n = 2;
  } else if (b >= 0xE0 && b <= 0xEF) {
    n = 3;
    if (b == 0xE0) lo = 0xA0;
    if (b == 0xED) hi = 0x9F;
  } else if (b >= 0xF0 && b <= 0xF4) {
    n = 4;
    if (b == 0xF0) lo = 0x90;
    if (b == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  return n;
}

}  // namespace

// A number as another program must read it: the shortest text that reads
// back as the same double ("10", "0.5", "1e-07", "1.0000001"). For
// numbers on a child's command line and in file names, where
// std::to_string's six decimals would pass 1e-07 as 0.000000 and
// 1.0000001 as 1.000000.
std::string exactNumber(double v) {
  char buf[32];  // the longest shortest form: "-2.2250738585072014e-308"
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : formatNumber("%.17g", v);
}

// `text` as printable, valid UTF-8 on one line: control characters
// (line breaks, escapes) and bytes that are not UTF-8 become '?', and the
// result is cut at `max_bytes` (ending in "...") on a character boundary.
// For text from a file shown to people or put in JSON.
std::string printableText(std::string_view text, std::size_t max_bytes) {
  // Whole characters, each printable or '?'.
  std::vector<std::string_view> chars;
  std::size_t total = 0;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8Length(text, i);
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if (n == 0 || b < 0x20 || b == 0x7F) {
      chars.push_back("?");
      i += 1;
    } else {
      chars.push_back(text.substr(i, n));
      i += n;
    }
    total += chars.back().size();
  }
  const bool cut = total > max_bytes;
  const std::size_t room = cut ? (max_bytes >= 3 ? max_bytes - 3 : 0) : max_bytes;
  std::string out;
  for (std::string_view c : chars) {
    if (out.size() + c.size() > room) break;
    out += c;
  }
  if (cut) out.append(std::min<std::size_t>(3, max_bytes), '.');
  return out;
}

// `text` as well-formed XML 1.0 character data, fit for an element's text
// and a quoted attribute value alike: & < > " ' become entities, and what
// XML 1.0 forbids even as a character reference (C0 controls other than
// tab, line feed and carriage return; U+FFFE; U+FFFF) and bytes that are
// not UTF-8 become U+FFFD. For names from a file written into SVG: one
// such byte makes the whole picture unreadable.
std::string xmlText(std::string_view text) {
  constexpr std::string_view kReplacement = "\xEF\xBF\xBD";  // U+FFFD
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8Length(text, i);
    const std::string_view c = text.substr(i, n == 0 ? 1 : n);
    i += c.size();
    const unsigned char b = static_cast<unsigned char>(c[0]);
    if (n == 0 || (b < 0x20 && b != '\t' && b != '\n' && b != '\r') || c == "\xEF\xBF\xBE" || c == "\xEF\xBF\xBF") {
      out += kReplacement;
      continue;
    }
    switch (b) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace earc
