// Text shown to people or put in JSON from files and command lines.
#include <doctest/doctest.h>

#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>

#include "earc/util/format.hpp"

using earc::exactNumber;
using earc::printableText;
using earc::utcTimeText;
using earc::xmlText;

TEST_CASE("printableText keeps valid UTF-8 and replaces control characters and bad bytes") {
  CHECK(printableText("plain text", 100) == "plain text");
  CHECK(printableText("caf\xc3\xa9 \xf0\x9f\xa4\x96", 100) == "caf\xc3\xa9 \xf0\x9f\xa4\x96");  // é and a 4-byte emoji
  CHECK(printableText("a\nb\tc\x1b[0m\x7f", 100) == "a?b?c?[0m?");
  CHECK(printableText("\xff\xfe", 100) == "??");                 // never UTF-8
  CHECK(printableText("\xc0\xaf", 100) == "??");                 // overlong '/'
  CHECK(printableText("\xed\xa0\x80", 100) == "???");            // a UTF-16 surrogate
  CHECK(printableText("\xf4\x90\x80\x80", 100) == "????");       // beyond U+10FFFF
  CHECK(printableText("x\xc3", 100) == "x?");                    // cut short
}

TEST_CASE("printableText cuts on a character boundary and marks the cut") {
  CHECK(printableText("abcdef", 6) == "abcdef");
  CHECK(printableText("abcdefg", 6) == "abc...");
  // "ab" then é (2 bytes): 5 bytes for 6 allowed would split é; cut before it.
  CHECK(printableText("ab\xc3\xa9\xc3\xa9xyz", 6) == "ab...");
  CHECK(printableText("abcdef", 2) == "..");
  CHECK(printableText("", 0).empty());
  for (std::size_t max = 0; max < 12; ++max) CHECK(printableText("\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9", max).size() <= max);
}

TEST_CASE("xmlText escapes markup and replaces what XML 1.0 forbids by U+FFFD") {
  const std::string fffd = "\xEF\xBF\xBD";
  CHECK(xmlText("a<b & \"c\" 'd'>") == "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;");
  CHECK(xmlText("ctl\x01x") == "ctl" + fffd + "x");
  CHECK(xmlText(std::string_view("\0", 1)) == fffd);
  CHECK(xmlText("\x1b[0m\x1f") == fffd + "[0m" + fffd);
  CHECK(xmlText("\xEF\xBF\xBE\xEF\xBF\xBF") == fffd + fffd);  // U+FFFE, U+FFFF
  CHECK(xmlText("\xff\xc3") == fffd + fffd);                      // not UTF-8
  // Allowed: tab, line breaks, DEL and C1 controls, U+FFFD itself, emoji.
  CHECK(xmlText("a\tb\nc\rd\x7f\xc2\x85") == "a\tb\nc\rd\x7f\xc2\x85");
  CHECK(xmlText("caf\xc3\xa9 \xef\xbf\xbd \xf0\x9f\xa4\x96") == "caf\xc3\xa9 \xef\xbf\xbd \xf0\x9f\xa4\x96");
}

TEST_CASE("utcTimeText writes ISO 8601 in UTC") {
  CHECK(utcTimeText(0) == "1970-01-01T00:00:00Z");
  CHECK(utcTimeText(1700000000) == "2023-11-14T22:13:20Z");
}

TEST_CASE("exactNumber writes the shortest text that reads back as the same number") {
  CHECK(exactNumber(10) == "10");
  CHECK(exactNumber(0.5) == "0.5");
  CHECK(exactNumber(0.1) == "0.1");
  CHECK(exactNumber(1e-7) == "1e-07");  // std::to_string: "0.000000"
  CHECK(exactNumber(1.0000001) == "1.0000001");
  CHECK(exactNumber(1e300) == "1e+300");
  for (double v : {1e-7, 1.0000001, 0.1 + 0.2, 123456.789012345, std::numeric_limits<double>::denorm_min(),
                   std::numeric_limits<double>::max(), -2.2250738585072014e-308})
    CHECK(std::strtod(exactNumber(v).c_str(), nullptr) == v);
}
