// Numbers in messages: six significant digits, never hundreds of digits
// (a 1e308 read from a file prints as 1e+308).
#pragma once

#include <cstdio>
#include <string>

namespace earc {

inline std::string formatNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace earc
