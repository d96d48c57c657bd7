// libFuzzer target: the path blob and key blob decoders, fed any bytes as a
// stored row's column. Bad bytes must end in CorruptRowError (a row the
// store skips and earc-db verify names); whatever decodes must encode back
// to the same bytes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "earc/experience/path_blob.hpp"
#include "earc/experience/sqlite.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const unsigned char> blob(data, size);
  try {
    std::vector<earc::Path> paths = earc::exp::decodePaths(blob, 7);
    // A decoded blob is canonical: encoding it again gives the input back.
    const std::vector<unsigned char> again = earc::exp::encodePaths(paths);
    if (again.size() != size || !std::equal(again.begin(), again.end(), data)) std::abort();
  } catch (const earc::exp::CorruptRowError&) {
  }
  try {
    std::vector<double> key = earc::exp::decodeKey(blob, 7);
    if (earc::exp::encodeKey(key).size() != size) std::abort();
  } catch (const earc::exp::CorruptRowError&) {
  }
  return 0;
}
