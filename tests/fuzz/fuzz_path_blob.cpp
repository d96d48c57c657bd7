// libFuzzer target: the path blob and key blob decoders, fed any bytes as a
// stored row's column. Bad bytes must end in CorruptRowError (a row the
// store skips and earc-db verify names); whatever decodes must encode to a
// blob that decodes to the same doubles, bit for bit, and that encodes to
// itself.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>
#include <vector>

#include "earc/experience/path_blob.hpp"
#include "earc/experience/sqlite.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const unsigned char> blob(data, size);
  try {
    const std::vector<earc::Path> paths = earc::exp::decodePaths(blob, 7);
    const std::vector<unsigned char> again = earc::exp::encodePaths(paths);
    const std::vector<earc::Path> back = earc::exp::decodePaths(again, 7);
    if (back.size() != paths.size()) std::abort();
    for (std::size_t r = 0; r < paths.size(); ++r)
      if (back[r].dim() != paths[r].dim() || back[r].raw().size() != paths[r].raw().size() ||
          std::memcmp(back[r].raw().data(), paths[r].raw().data(), paths[r].raw().size() * sizeof(double)) != 0)
        std::abort();
    if (earc::exp::encodePaths(back) != again) std::abort();
  } catch (const earc::exp::CorruptRowError&) {
  }
  try {
    std::vector<double> key = earc::exp::decodeKey(blob, 7);
    if (earc::exp::encodeKey(key).size() != size) std::abort();
  } catch (const earc::exp::CorruptRowError&) {
  }
  return 0;
}
