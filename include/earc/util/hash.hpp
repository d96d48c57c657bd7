// A stable 64-bit hash (FNV-1a): the same on every machine and run, for
// seeds derived from names and for checksums of files we write.
#pragma once

#include <cstdint>
#include <string_view>

namespace earc {

inline std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t h = 1469598103934665603ULL) {
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ULL;
  return h;
}

}  // namespace earc
