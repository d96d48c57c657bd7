#include "earc/experience/path_blob.hpp"

#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "earc/experience/sqlite.hpp"

namespace earc::exp {

namespace {

void putU16(std::vector<unsigned char>& out, std::size_t at, std::uint16_t v) {
  out[at] = static_cast<unsigned char>(v & 0xff);
  out[at + 1] = static_cast<unsigned char>(v >> 8);
}
void putU32(std::vector<unsigned char>& out, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out[at + static_cast<std::size_t>(i)] = static_cast<unsigned char>(v >> (8 * i));
}
void putDouble(unsigned char* out, double v) {
  auto bits = std::bit_cast<std::uint64_t>(v);
  for (int i = 0; i < 8; ++i) out[i] = static_cast<unsigned char>(bits >> (8 * i));
}
std::uint16_t getU16(const unsigned char* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
std::uint32_t getU32(const unsigned char* p) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
double getDouble(const unsigned char* p) {
  std::uint64_t bits = 0;
  for (int i = 7; i >= 0; --i) bits = (bits << 8) | p[i];
  return std::bit_cast<double>(bits);
}

}  // namespace

std::vector<unsigned char> encodePaths(const std::vector<Path>& paths) {
  if (paths.empty() || paths.size() > static_cast<std::size_t>(kMaxBlobRobots))
    throw std::invalid_argument("encodePaths: need 1.." + std::to_string(kMaxBlobRobots) + " paths");
  const int dim = paths.front().dim();
  const std::size_t steps = paths.front().size();
  if (dim < 1 || dim > kMaxBlobDim) throw std::invalid_argument("encodePaths: dimension out of range");
  if (steps == 0 || steps > 0xffffffffu) throw std::invalid_argument("encodePaths: empty path");
  for (const Path& p : paths)
    if (p.dim() != dim || p.size() != steps)
      throw std::invalid_argument("encodePaths: paths differ in dimension or length");
  std::vector<unsigned char> out(kPathBlobHeaderSize + paths.size() * steps * static_cast<std::size_t>(dim) * 8);
  std::memcpy(out.data(), kPathBlobMagic, 4);
  putU16(out, 4, kPathBlobVersion);
  out[6] = 8;
  out[7] = 0;
  putU16(out, 8, static_cast<std::uint16_t>(paths.size()));
  putU16(out, 10, static_cast<std::uint16_t>(dim));
  putU32(out, 12, static_cast<std::uint32_t>(steps));
  unsigned char* w = out.data() + kPathBlobHeaderSize;
  for (const Path& p : paths)
    for (double v : p.raw()) {
      if (!std::isfinite(v)) throw std::invalid_argument("encodePaths: non-finite coordinate");
      putDouble(w, v);
      w += 8;
    }
  return out;
}

PathBlobHeader readPathBlobHeader(std::span<const unsigned char> blob, std::int64_t row) {
  auto fail = [row](const std::string& why) { throw CorruptRowError(row, "path blob: " + why); };
  if (blob.size() < kPathBlobHeaderSize)
    fail("too short (" + std::to_string(blob.size()) + " bytes; the header alone is " +
         std::to_string(kPathBlobHeaderSize) + ")");
  const unsigned char* h = blob.data();
  if (std::memcmp(h, kPathBlobMagic, 4) != 0) fail("bad magic (expected \"EPTH\"): not an earc path blob");
  const std::uint16_t version = getU16(h + 4);
  if (version != kPathBlobVersion)
    fail("format version " + std::to_string(version) + " is not the supported version " +
         std::to_string(kPathBlobVersion) + "; rebuild the database or use the earc that wrote it");
  if (h[6] != 8) fail("scalar size " + std::to_string(h[6]) + " bytes, expected 8 (double)");
  if (h[7] != 0) fail("unknown flags " + std::to_string(h[7]));
  PathBlobHeader header{getU16(h + 8), getU16(h + 10), getU32(h + 12)};
  if (header.robots < 1 || header.robots > kMaxBlobRobots)
    fail("robot count " + std::to_string(header.robots) + " outside 1.." + std::to_string(kMaxBlobRobots));
  if (header.dim < 1 || header.dim > kMaxBlobDim)
    fail("dimension " + std::to_string(header.dim) + " outside 1.." + std::to_string(kMaxBlobDim));
  if (header.steps < 1) fail("zero steps");
  return header;
}

std::vector<Path> decodePaths(std::span<const unsigned char> blob, std::int64_t row) {
  auto fail = [row](const std::string& why) { throw CorruptRowError(row, "path blob: " + why); };
  const PathBlobHeader header = readPathBlobHeader(blob, row);
  const std::size_t robots = static_cast<std::size_t>(header.robots);
  const std::size_t dim = static_cast<std::size_t>(header.dim);
  const std::size_t steps = header.steps;
  // robots, dim <= 64 and steps < 2^32: the product fits in 64 bits.
  const std::size_t expected = header.expectedSize();
  if (blob.size() != expected)
    fail("length " + std::to_string(blob.size()) + " bytes, but the header says " + std::to_string(robots) +
         " robots x " + std::to_string(dim) + " coordinates x " + std::to_string(steps) + " steps = " +
         std::to_string(expected) + " bytes");
  const unsigned char* h = blob.data();
  std::vector<Path> paths;
  paths.reserve(robots);
  const unsigned char* p = h + kPathBlobHeaderSize;
  for (std::size_t r = 0; r < robots; ++r) {
    Path path(static_cast<int>(dim));
    auto& raw = path.raw();
    raw.resize(dim * steps);
    for (std::size_t i = 0; i < dim * steps; ++i, p += 8) {
      raw[i] = getDouble(p);
      if (!std::isfinite(raw[i]))
        fail("robot " + std::to_string(r) + " step " + std::to_string(i / dim) + " coordinate " +
             std::to_string(i % dim) + " is not finite");
    }
    paths.push_back(std::move(path));
  }
  return paths;
}

std::vector<unsigned char> encodeKey(std::span<const double> key) {
  std::vector<unsigned char> out(key.size() * 8);
  for (std::size_t i = 0; i < key.size(); ++i) {
    if (!std::isfinite(key[i])) throw std::invalid_argument("encodeKey: non-finite value");
    putDouble(out.data() + 8 * i, key[i]);
  }
  return out;
}

std::vector<double> decodeKey(std::span<const unsigned char> blob, std::int64_t row) {
  if (blob.size() % 8 != 0)
    throw CorruptRowError(row, "key blob: length " + std::to_string(blob.size()) +
                                   " bytes is not a whole number of doubles");
  std::vector<double> key(blob.size() / 8);
  for (std::size_t i = 0; i < key.size(); ++i) {
    key[i] = getDouble(blob.data() + 8 * i);
    if (!std::isfinite(key[i])) throw CorruptRowError(row, "key blob: value " + std::to_string(i) + " is not finite");
  }
  return key;
}

}  // namespace earc::exp
