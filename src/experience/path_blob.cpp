#include "earc/experience/path_blob.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "earc/experience/sqlite.hpp"

#if defined(__x86_64__)
#include <nmmintrin.h>
#endif

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

// Version 2: a run between keyframes goes on while every state in it is
// within this many units in the last place of its straight-line estimate
// (its difference then takes one varint byte), and for at most kMaxRun
// steps, which bounds the encoder's work to kMaxRun checks per state.
constexpr std::uint64_t kRunUlps = 63;
constexpr std::size_t kMaxRun = 64;

std::uint64_t bitsOf(double v) { return std::bit_cast<std::uint64_t>(v); }
// Two's-complement difference as zigzag: 0, -1, 1, -2, ... -> 0, 1, 2, 3, ...
std::uint64_t zigzag(std::uint64_t diff) {
  const auto d = static_cast<std::int64_t>(diff);
  return (diff << 1) ^ static_cast<std::uint64_t>(d >> 63);
}
std::uint64_t unzigzag(std::uint64_t z) { return (z >> 1) ^ (~(z & 1) + 1); }

void putVarint(std::vector<unsigned char>& out, std::uint64_t z) {
  while (z >= 0x80) {
    out.push_back(static_cast<unsigned char>((z & 0x7f) | 0x80));
    z >>= 7;
  }
  out.push_back(static_cast<unsigned char>(z));
}

struct Shape {
  int dim;
  std::size_t steps;
};
Shape checkEncodable(const std::vector<Path>& paths) {
  if (paths.empty() || paths.size() > static_cast<std::size_t>(kMaxBlobRobots))
    throw std::invalid_argument("encodePaths: need 1.." + std::to_string(kMaxBlobRobots) + " paths");
  const int dim = paths.front().dim();
  const std::size_t steps = paths.front().size();
  if (dim < 1 || dim > kMaxBlobDim) throw std::invalid_argument("encodePaths: dimension out of range");
  if (steps == 0 || steps > 0xffffffffu) throw std::invalid_argument("encodePaths: empty path");
  for (const Path& p : paths) {
    if (p.dim() != dim || p.size() != steps)
      throw std::invalid_argument("encodePaths: paths differ in dimension or length");
    for (double v : p.raw())
      if (!std::isfinite(v)) throw std::invalid_argument("encodePaths: non-finite coordinate");
  }
  return {dim, steps};
}

std::vector<unsigned char> blobHeader(std::uint16_t version, std::size_t robots, Shape shape) {
  std::vector<unsigned char> out(kPathBlobHeaderSize);
  std::memcpy(out.data(), kPathBlobMagic, 4);
  putU16(out, 4, version);
  out[6] = 8;
  out[7] = 0;
  putU16(out, 8, static_cast<std::uint16_t>(robots));
  putU16(out, 10, static_cast<std::uint16_t>(shape.dim));
  putU32(out, 12, static_cast<std::uint32_t>(shape.steps));
  return out;
}

// What version 2 stores for coordinate d at step t between keyframes i
// and j: the zigzag-coded difference from its estimate.
std::uint64_t difference(const Path& p, std::size_t i, std::size_t j, std::size_t t, std::size_t d) {
  return zigzag(bitsOf(p.at(t)[d]) - bitsOf(keyframeEstimate(p.at(i)[d], p.at(j)[d], i, j, t)));
}

// Whether every state strictly between steps i and j is close to its
// estimate.
bool runHolds(const Path& p, std::size_t i, std::size_t j) {
  const auto dim = static_cast<std::size_t>(p.dim());
  for (std::size_t t = i + 1; t < j; ++t)
    for (std::size_t d = 0; d < dim; ++d)
      if (difference(p, i, j, t, d) > 2 * kRunUlps) return false;
  return true;
}

void encodeRobotV2(const Path& p, std::vector<unsigned char>& out) {
  const std::size_t steps = p.size();
  const auto dim = static_cast<std::size_t>(p.dim());
  std::vector<std::size_t> keys{0};
  for (std::size_t i = 0; i + 1 < steps;) {
    std::size_t j = i + 1;
    while (j + 1 < steps && j + 1 - i <= kMaxRun && runHolds(p, i, j + 1)) ++j;
    keys.push_back(j);
    i = j;
  }
  std::size_t at = out.size();
  out.resize(at + 4 + keys.size() * (4 + 8 * dim));
  putU32(out, at, static_cast<std::uint32_t>(keys.size()));
  at += 4;
  for (std::size_t k : keys) {
    putU32(out, at, static_cast<std::uint32_t>(k));
    at += 4;
  }
  for (std::size_t k : keys)
    for (std::size_t d = 0; d < dim; ++d, at += 8) putDouble(out.data() + at, p.at(k)[d]);
  for (std::size_t s = 0; s + 1 < keys.size(); ++s)
    for (std::size_t t = keys[s] + 1; t < keys[s + 1]; ++t)
      for (std::size_t d = 0; d < dim; ++d) putVarint(out, difference(p, keys[s], keys[s + 1], t, d));
}

}  // namespace

double keyframeEstimate(double a, double b, std::size_t i, std::size_t j, std::size_t t) {
  const double s = static_cast<double>(t - i) / static_cast<double>(j - i);
  return std::fma(s, b, (1.0 - s) * a);  // one rounding for the sum, never contracted differently
}

std::uint32_t crc32cPortable(std::span<const unsigned char> bytes) {
  // Slicing by 8: eight bytes a step through eight tables (8 KiB).
  static constexpr auto kTables = [] {
    std::array<std::array<std::uint32_t, 256>, 8> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0x82f63b78u ^ (c >> 1) : c >> 1;
      t[0][i] = c;
    }
    for (std::size_t k = 1; k < 8; ++k)
      for (std::size_t i = 0; i < 256; ++i) t[k][i] = (t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xff];
    return t;
  }();
  const auto& t = kTables;
  std::uint32_t c = 0xffffffffu;
  const unsigned char* p = bytes.data();
  std::size_t n = bytes.size();
  for (; n >= 8; n -= 8, p += 8) {
    const std::uint32_t lo = getU32(p) ^ c, hi = getU32(p + 4);
    c = t[7][lo & 0xff] ^ t[6][(lo >> 8) & 0xff] ^ t[5][(lo >> 16) & 0xff] ^ t[4][lo >> 24] ^ t[3][hi & 0xff] ^
        t[2][(hi >> 8) & 0xff] ^ t[1][(hi >> 16) & 0xff] ^ t[0][hi >> 24];
  }
  for (; n > 0; --n, ++p) c = t[0][(c ^ *p) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

namespace {

#if defined(__x86_64__)
// SSE 4.2's crc32 instruction computes CRC-32C, eight bytes at a time:
// a plan checks every row it reads (ten a query), and the tables' few
// microseconds a query were a noticeable part of its hundred.
__attribute__((target("sse4.2"))) std::uint32_t crc32cSse42(std::span<const unsigned char> bytes) {
  std::uint64_t c = 0xffffffffu;
  const unsigned char* p = bytes.data();
  std::size_t n = bytes.size();
  for (; n >= 8; n -= 8, p += 8) {
    std::uint64_t v;
    std::memcpy(&v, p, 8);  // little-endian on x86: the bytes in order
    c = _mm_crc32_u64(c, v);
  }
  auto c32 = static_cast<std::uint32_t>(c);
  for (; n > 0; --n, ++p) c32 = _mm_crc32_u8(c32, *p);
  return c32 ^ 0xffffffffu;
}
#endif

}  // namespace

std::uint32_t crc32c(std::span<const unsigned char> bytes) {
#if defined(__x86_64__)
  static const bool sse42 = __builtin_cpu_supports("sse4.2");
  if (sse42) return crc32cSse42(bytes);
#endif
  return crc32cPortable(bytes);
}

namespace {

std::vector<unsigned char> encodeKeyframed(const std::vector<Path>& paths, std::uint16_t version) {
  const Shape shape = checkEncodable(paths);
  std::vector<unsigned char> out = blobHeader(version, paths.size(), shape);
  for (const Path& p : paths) encodeRobotV2(p, out);
  return out;
}

}  // namespace

std::vector<unsigned char> encodePaths(const std::vector<Path>& paths) {
  static_assert(kPathBlobVersion == 3, "encodePaths writes version 3");
  std::vector<unsigned char> out = encodeKeyframed(paths, 3);
  const std::uint32_t sum = crc32c(out);
  out.resize(out.size() + 4);
  putU32(out, out.size() - 4, sum);
  return out;
}

std::vector<unsigned char> encodePathsV2(const std::vector<Path>& paths) { return encodeKeyframed(paths, 2); }

std::vector<unsigned char> encodePathsV1(const std::vector<Path>& paths) {
  const Shape shape = checkEncodable(paths);
  std::vector<unsigned char> out = blobHeader(1, paths.size(), shape);
  out.resize(kPathBlobHeaderSize + paths.size() * shape.steps * static_cast<std::size_t>(shape.dim) * 8);
  unsigned char* w = out.data() + kPathBlobHeaderSize;
  for (const Path& p : paths)
    for (double v : p.raw()) {
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
  if (version < 1 || version > 3)
    fail("format version " + std::to_string(version) + " is not a supported version (1, 2 or 3)" +
         "; rebuild the database or use the earc that wrote it");
  if (h[6] != 8) fail("scalar size " + std::to_string(h[6]) + " bytes, expected 8 (double)");
  if (h[7] != 0) fail("unknown flags " + std::to_string(h[7]));
  PathBlobHeader header{version, getU16(h + 8), getU16(h + 10), getU32(h + 12)};
  if (header.robots < 1 || header.robots > kMaxBlobRobots)
    fail("robot count " + std::to_string(header.robots) + " outside 1.." + std::to_string(kMaxBlobRobots));
  if (header.dim < 1 || header.dim > kMaxBlobDim)
    fail("dimension " + std::to_string(header.dim) + " outside 1.." + std::to_string(kMaxBlobDim));
  if (header.steps < 1) fail("zero steps");
  return header;
}

namespace {

std::vector<Path> decodeV1(std::span<const unsigned char> blob, const PathBlobHeader& header, std::int64_t row) {
  auto fail = [row](const std::string& why) { throw CorruptRowError(row, "path blob: " + why); };
  const std::size_t robots = static_cast<std::size_t>(header.robots);
  const std::size_t dim = static_cast<std::size_t>(header.dim);
  const std::size_t steps = header.steps;
  // robots, dim <= 64 and steps < 2^32: the product fits in 64 bits.
  const std::size_t expected = kPathBlobHeaderSize + 8 * robots * dim * steps;
  if (blob.size() != expected)
    fail("length " + std::to_string(blob.size()) + " bytes, but the header says " + std::to_string(robots) +
         " robots x " + std::to_string(dim) + " coordinates x " + std::to_string(steps) + " steps = " +
         std::to_string(expected) + " bytes");
  std::vector<Path> paths;
  paths.reserve(robots);
  const unsigned char* p = blob.data() + kPathBlobHeaderSize;
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

// Versions 2 and 3: `trailer` bytes at the end (version 3's checksum) are
// not paths; messages give the whole blob's length.
std::vector<Path> decodeKeyframed(std::span<const unsigned char> blob, const PathBlobHeader& header, std::int64_t row,
                                  std::size_t trailer) {
  auto fail = [row](const std::string& why) { throw CorruptRowError(row, "path blob: " + why); };
  const std::size_t robots = static_cast<std::size_t>(header.robots);
  const std::size_t dim = static_cast<std::size_t>(header.dim);
  const std::size_t steps = header.steps;
  const unsigned char* p = blob.data() + kPathBlobHeaderSize;
  const unsigned char* const end = blob.data() + blob.size() - trailer;
  auto left = [&] { return static_cast<std::size_t>(end - p); };
  auto truncated = [&](std::size_t r, const char* what) {
    fail("length " + std::to_string(blob.size()) + " bytes ends inside robot " + std::to_string(r) + "'s " + what);
  };
  std::vector<Path> paths;
  paths.reserve(robots);
  for (std::size_t r = 0; r < robots; ++r) {
    const std::string who = "robot " + std::to_string(r);
    if (left() < 4) truncated(r, "keyframe count");
    const std::size_t count = getU32(p);
    p += 4;
    if (count < 1 || count > steps)
      fail(who + ": " + std::to_string(count) + " keyframes, outside 1.." + std::to_string(steps) + " steps");
    // Sizes checked before anything is allocated: count <= steps < 2^32, dim <= 64.
    if (left() / 4 < count) truncated(r, "keyframe steps");
    std::vector<std::size_t> keys(count);
    for (std::size_t k = 0; k < count; ++k, p += 4) {
      keys[k] = getU32(p);
      if ((k == 0 && keys[k] != 0) || (k > 0 && keys[k] <= keys[k - 1]))
        fail(who + ": keyframe steps must start at 0 and increase (keyframe " + std::to_string(k) + " is step " +
             std::to_string(keys[k]) + ")");
    }
    if (keys.back() != steps - 1)
      fail(who + ": last keyframe at step " + std::to_string(keys.back()) + ", not the last step " +
           std::to_string(steps - 1));
    if (left() / (8 * dim) < count) truncated(r, "keyframe states");
    // Every other coordinate takes at least one byte.
    if (left() - count * 8 * dim < (steps - count) * dim) truncated(r, "differences");
    Path path(static_cast<int>(dim));
    auto& raw = path.raw();
    raw.resize(dim * steps);
    auto notFinite = [&](std::size_t t, std::size_t d) {
      fail(who + " step " + std::to_string(t) + " coordinate " + std::to_string(d) + " is not finite");
    };
    for (std::size_t k : keys)
      for (std::size_t d = 0; d < dim; ++d, p += 8) {
        raw[k * dim + d] = getDouble(p);
        if (!std::isfinite(raw[k * dim + d])) notFinite(k, d);
      }
    for (std::size_t s = 0; s + 1 < count; ++s)
      for (std::size_t t = keys[s] + 1; t < keys[s + 1]; ++t)
        for (std::size_t d = 0; d < dim; ++d) {
          std::uint64_t z = 0;
          for (int shift = 0;; shift += 7) {
            if (p == end) truncated(r, "differences");
            const unsigned char byte = *p++;
            if (shift == 63 && byte > 1) fail(who + ": a difference longer than 64 bits");
            z |= static_cast<std::uint64_t>(byte & 0x7f) << shift;
            if (!(byte & 0x80)) break;
          }
          const double estimate = keyframeEstimate(raw[keys[s] * dim + d], raw[keys[s + 1] * dim + d], keys[s],
                                                   keys[s + 1], t);
          raw[t * dim + d] = std::bit_cast<double>(bitsOf(estimate) + unzigzag(z));
          if (!std::isfinite(raw[t * dim + d])) notFinite(t, d);
        }
    paths.push_back(std::move(path));
  }
  if (p != end)
    fail("length " + std::to_string(blob.size()) + " bytes, " + std::to_string(left()) +
         " more than its paths take");
  return paths;
}

}  // namespace

std::vector<Path> decodePaths(std::span<const unsigned char> blob, std::int64_t row) {
  const PathBlobHeader header = readPathBlobHeader(blob, row);
  if (header.version == 1) return decodeV1(blob, header, row);
  if (header.version == 2) return decodeKeyframed(blob, header, row, 0);
  // Version 3: the structure first, whose errors say what is cut short or
  // left over; then the checksum, which finds what changed inside.
  if (blob.size() < kPathBlobHeaderSize + 4)
    throw CorruptRowError(row, "path blob: length " + std::to_string(blob.size()) +
                                   " bytes ends inside its header and checksum");
  std::vector<Path> paths = decodeKeyframed(blob, header, row, 4);
  const std::span<const unsigned char> body = blob.first(blob.size() - 4);
  const std::uint32_t stored = getU32(blob.data() + body.size()), computed = crc32c(body);
  if (stored != computed) {
    char why[160];
    std::snprintf(why, sizeof why,
                  "path blob: checksum %08x, but its bytes give %08x: changed after it was written", stored, computed);
    throw CorruptRowError(row, why);
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
