// The path blob format: versions 1, 2 and 3 give back exactly the doubles
// stored, versions 2 and 3 are small for straight runs, version 3 finds a
// changed byte by its checksum, and corrupt blobs are rejected, each error
// naming the row.
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "earc/experience/path_blob.hpp"
#include "earc/experience/sqlite.hpp"

using namespace earc;
using namespace earc::exp;

namespace {

std::vector<Path> twoPaths() {
  std::vector<Path> paths;
  for (int r = 0; r < 2; ++r) {
    Path p(3);
    for (int t = 0; t < 4; ++t) p.push(std::vector<double>{0.1 * t + r, -0.25 * t, 1e-300 * t});
    paths.push_back(p);
  }
  return paths;
}

// Bit for bit: == would take -0.0 for 0.0.
bool sameBits(const std::vector<Path>& a, const std::vector<Path>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t r = 0; r < a.size(); ++r)
    if (a[r].dim() != b[r].dim() || a[r].raw().size() != b[r].raw().size() ||
        std::memcmp(a[r].raw().data(), b[r].raw().data(), a[r].raw().size() * sizeof(double)) != 0)
      return false;
  return true;
}

// Paths that are hard to predict: a random walk, straight runs longer than
// a run may be, a run through zero, -0.0, huge and subnormal values.
std::vector<Path> awkwardPaths() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> step(-0.3, 0.3);
  std::vector<Path> paths(3, Path(3));
  double x = 1.5, y = -2.0, h = 0.0;
  for (std::size_t t = 0; t < 300; ++t) {
    x += step(rng);
    y += step(rng);
    h = t % 7 == 0 ? -0.0 : h + step(rng);
    paths[0].push(std::vector<double>{x, y, h});
    const double s = static_cast<double>(t) / 299.0;
    paths[1].push(std::vector<double>{(1.0 - s) * -3.0 + s * 4.0, 0.25 * static_cast<double>(t % 100), 1e300 * s});
    paths[2].push(std::vector<double>{4.9e-324 * static_cast<double>(t % 3), t < 150 ? 0.0 : 1.0, -7.5});
  }
  return paths;
}

std::vector<unsigned char> headerBytes(std::uint16_t version, std::uint16_t robots, std::uint16_t dim,
                                       std::uint32_t steps) {
  std::vector<unsigned char> b{'E', 'P', 'T', 'H', static_cast<unsigned char>(version),
                               static_cast<unsigned char>(version >> 8), 8, 0,
                               static_cast<unsigned char>(robots), 0, static_cast<unsigned char>(dim), 0};
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<unsigned char>(steps >> (8 * i)));
  return b;
}
void putU32(std::vector<unsigned char>& b, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<unsigned char>(v >> (8 * i)));
}
void putDouble(std::vector<unsigned char>& b, double v) {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  for (int i = 0; i < 8; ++i) b.push_back(static_cast<unsigned char>(bits >> (8 * i)));
}
// Version 2, one robot, one coordinate, 3 steps: keyframes at 0 and 2
// (1.0 and 3.0), step 1 given by the varint bytes.
std::vector<unsigned char> threeSteps(std::vector<unsigned char> varint) {
  auto b = headerBytes(2, 1, 1, 3);
  putU32(b, 2);
  putU32(b, 0);
  putU32(b, 2);
  putDouble(b, 1.0);
  putDouble(b, 3.0);
  b.insert(b.end(), varint.begin(), varint.end());
  return b;
}

std::string decodeError(std::span<const unsigned char> blob, std::int64_t row) {
  try {
    decodePaths(blob, row);
  } catch (const CorruptRowError& e) {
    CHECK(e.row() == row);
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a path blob decodes to exactly the paths it was encoded from") {
  for (const auto& paths : {twoPaths(), awkwardPaths()}) {
    auto blob = encodePaths(paths);
    CHECK(std::string(blob.begin(), blob.begin() + 4) == "EPTH");
    CHECK(sameBits(decodePaths(blob, 1), paths));
    PathBlobHeader h = readPathBlobHeader(blob, 1);
    CHECK(h.version == kPathBlobVersion);
    CHECK(h.robots == static_cast<int>(paths.size()));
    CHECK(h.dim == 3);
    CHECK(h.steps == paths.front().size());
  }
  Path one(2);
  one.push(std::vector<double>{-0.0, 5.0});
  CHECK(sameBits(decodePaths(encodePaths({one}), 1), {one}));
}

TEST_CASE("a version 3 blob is version 2's with a CRC-32C of everything before it at its end") {
  for (const auto& paths : {twoPaths(), awkwardPaths()}) {
    const auto v3 = encodePaths(paths), v2 = encodePathsV2(paths);
    REQUIRE(v3.size() == v2.size() + 4);
    CHECK(readPathBlobHeader(v2, 1).version == 2);
    CHECK(sameBits(decodePaths(v2, 1), paths));  // still read
    CHECK(std::equal(v2.begin() + 6, v2.end(), v3.begin() + 6));  // but the version, the same bytes
    const std::span<const unsigned char> body(v3.data(), v3.size() - 4);
    const std::uint32_t stored = static_cast<std::uint32_t>(v3[v3.size() - 4]) | v3[v3.size() - 3] << 8 |
                                 v3[v3.size() - 2] << 16 | static_cast<std::uint32_t>(v3[v3.size() - 1]) << 24;
    CHECK(stored == crc32c(body));
  }
  // The check value of CRC-32C: its CRC of "123456789".
  const std::string nine = "123456789";
  const std::span<const unsigned char> nine_bytes(reinterpret_cast<const unsigned char*>(nine.data()), nine.size());
  CHECK(crc32c(nine_bytes) == 0xe3069283u);
  CHECK(crc32cPortable(nine_bytes) == 0xe3069283u);
  // The processor's instruction, the tables (eight bytes a step) and a bit
  // at a time agree at every length and alignment.
  std::mt19937_64 rng(3);
  std::vector<unsigned char> bytes(300);
  for (auto& b : bytes) b = static_cast<unsigned char>(rng());
  auto bitwise = [](std::span<const unsigned char> b) {
    std::uint32_t c = 0xffffffffu;
    for (unsigned char x : b) {
      c ^= x;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0x82f63b78u ^ (c >> 1) : c >> 1;
    }
    return c ^ 0xffffffffu;
  };
  for (std::size_t from = 0; from < 9; ++from)
    for (std::size_t n = 0; from + n <= bytes.size(); n += 7) {
      const std::span<const unsigned char> part(bytes.data() + from, n);
      REQUIRE(crc32cPortable(part) == bitwise(part));
      REQUIRE(crc32c(part) == bitwise(part));
    }
}

TEST_CASE("every single flipped bit of a version 3 blob is refused, naming the row") {
  // A flip in a difference or a keyframe's state still decodes to finite
  // numbers nearly always: only the checksum finds it.
  const auto blob = encodePaths(awkwardPaths());
  int by_checksum = 0;
  for (std::size_t byte = 0; byte < blob.size(); ++byte)
    for (int bit = 0; bit < 8; ++bit) {
      auto flipped = blob;
      flipped[byte] ^= static_cast<unsigned char>(1u << bit);
      const std::string msg = decodeError(flipped, 11);
      CAPTURE(byte);
      CAPTURE(bit);
      REQUIRE(msg.find("row 11") != std::string::npos);
      if (msg.find("changed after it was written") != std::string::npos) ++by_checksum;
    }
  // Most flips decode as valid paths but for the checksum.
  CHECK(by_checksum > static_cast<int>(blob.size()) * 8 / 2);
}

TEST_CASE("a version 1 path blob is still read, exactly") {
  for (const auto& paths : {twoPaths(), awkwardPaths()}) {
    auto blob = encodePathsV1(paths);
    CHECK(blob.size() == kPathBlobHeaderSize + paths.size() * paths.front().size() * 3 * 8);
    CHECK(readPathBlobHeader(blob, 1).version == 1);
    CHECK(sameBits(decodePaths(blob, 1), paths));
  }
}

TEST_CASE("version 2 stores straight runs in a fraction of version 1's bytes") {
  // Two robots moving in straight lines, as a stored experience mostly does.
  std::vector<Path> paths(2, Path(3));
  for (std::size_t t = 0; t < 200; ++t) {
    const double s = static_cast<double>(t) / 199.0;
    paths[0].push(std::vector<double>{(1.0 - s) * 0.3 + s * 4.7, (1.0 - s) * -1.1 + s * 2.9, 0.5});
    paths[1].push(std::vector<double>{2.0, (1.0 - s) * 3.3 + s * -0.4, (1.0 - s) * 1.0 + s * -2.0});
  }
  const auto v2 = encodePaths(paths), v1 = encodePathsV1(paths);
  CHECK(sameBits(decodePaths(v2, 1), paths));
  CHECK(v2.size() * 5 < v1.size());
  // A random walk does not shrink, but costs little more.
  const auto walk = awkwardPaths();
  CHECK(encodePaths(walk).size() < encodePathsV1(walk).size() * 3 / 2);
}

TEST_CASE("a path blob stores numbers little-endian whatever the host") {
  Path p(1);
  p.push(std::vector<double>{1.0});  // 0x3ff0000000000000
  auto blob = encodePaths({p});
  // Keyframe count 1, keyframe step 0, its state, the checksum.
  REQUIRE(blob.size() == kPathBlobHeaderSize + 4 + 4 + 8 + 4);
  const std::uint32_t sum = crc32c(std::span<const unsigned char>(blob.data(), blob.size() - 4));
  CHECK(blob[blob.size() - 4] == (sum & 0xff));
  CHECK(blob[blob.size() - 1] == (sum >> 24));
  CHECK(blob[kPathBlobHeaderSize] == 1);
  CHECK(blob[kPathBlobHeaderSize + 3] == 0);
  CHECK(blob[kPathBlobHeaderSize + 8 + 7] == 0x3f);
  CHECK(blob[kPathBlobHeaderSize + 8 + 6] == 0xf0);
  CHECK(blob[kPathBlobHeaderSize + 8] == 0x00);
  auto v1 = encodePathsV1({p});
  REQUIRE(v1.size() == kPathBlobHeaderSize + 8);
  CHECK(v1[kPathBlobHeaderSize + 7] == 0x3f);
}

TEST_CASE("a version 2 difference is the zigzag varint of the bit patterns") {
  // Step 1's estimate is 2.0 exactly: difference 0 is one byte 0.
  CHECK(decodePaths(threeSteps({0}), 1)[0].at(1)[0] == 2.0);
  // +1 unit in the last place is zigzag 2, -1 is zigzag 1.
  CHECK(decodePaths(threeSteps({2}), 1)[0].at(1)[0] == std::nextafter(2.0, 3.0));
  CHECK(decodePaths(threeSteps({1}), 1)[0].at(1)[0] == std::nextafter(2.0, 1.0));
  // Two varint bytes: zigzag 128 = +64 units.
  const auto p = decodePaths(threeSteps({0x80, 0x01}), 1)[0].at(1)[0];
  CHECK(std::bit_cast<std::uint64_t>(p) == std::bit_cast<std::uint64_t>(2.0) + 64);
}

TEST_CASE("a path blob with a bad magic is rejected naming the row") {
  auto blob = encodePaths(twoPaths());
  blob[0] = 'X';
  auto msg = decodeError(blob, 42);
  CHECK(msg.find("row 42") != std::string::npos);
  CHECK(msg.find("magic") != std::string::npos);
}

TEST_CASE("a path blob of another format version is rejected with what to do") {
  auto blob = encodePaths(twoPaths());
  blob[4] = 4;
  auto msg = decodeError(blob, 7);
  CHECK(msg.find("format version 4") != std::string::npos);
  CHECK(msg.find("rebuild") != std::string::npos);
}

TEST_CASE("a path blob with another scalar size is rejected") {
  auto blob = encodePaths(twoPaths());
  blob[6] = 4;
  CHECK(decodeError(blob, 3).find("scalar size 4") != std::string::npos);
}

TEST_CASE("a truncated or overlong path blob is rejected by its length") {
  for (const auto& blob : {encodePaths(awkwardPaths()), encodePathsV2(awkwardPaths()), encodePathsV1(twoPaths())}) {
    for (std::size_t cut : {std::size_t{1}, std::size_t{8}, blob.size() / 2, blob.size() - kPathBlobHeaderSize}) {
      auto shorter = std::vector<unsigned char>(blob.begin(), blob.end() - static_cast<std::ptrdiff_t>(cut));
      CHECK(decodeError(shorter, 5).find("length") != std::string::npos);
    }
    auto longer = blob;
    longer.push_back(0);
    CHECK(decodeError(longer, 5).find("length") != std::string::npos);
    auto header_only = std::vector<unsigned char>(blob.begin(), blob.begin() + 10);
    CHECK(decodeError(header_only, 5).find("too short") != std::string::npos);
  }
}

TEST_CASE("a version 2 blob with impossible keyframes or differences is rejected") {
  auto keyframes = [](std::vector<std::uint32_t> steps) {
    auto b = headerBytes(2, 1, 1, 3);
    putU32(b, static_cast<std::uint32_t>(steps.size()));
    for (auto k : steps) putU32(b, k);
    for (std::size_t k = 0; k < steps.size(); ++k) putDouble(b, 1.0);
    for (std::size_t k = steps.size(); k < 3; ++k) b.push_back(0);
    return b;
  };
  CHECK(decodePaths(keyframes({0, 1, 2}), 1)[0].size() == 3);
  CHECK(decodeError(keyframes({}), 4).find("0 keyframes") != std::string::npos);
  CHECK(decodeError(keyframes({0, 1, 2, 2}), 4).find("4 keyframes, outside 1..3") != std::string::npos);
  CHECK(decodeError(keyframes({1, 2}), 4).find("start at 0 and increase") != std::string::npos);
  CHECK(decodeError(keyframes({0, 0, 2}), 4).find("start at 0 and increase") != std::string::npos);
  CHECK(decodeError(keyframes({0, 1}), 4).find("not the last step 2") != std::string::npos);
  // A claimed 2^32 - 1 steps in a few bytes: refused before allocating.
  auto huge = headerBytes(2, 1, 1, 0xffffffffu);
  putU32(huge, 2);
  putU32(huge, 0);
  putU32(huge, 0xfffffffeu);
  putDouble(huge, 1.0);
  putDouble(huge, 2.0);
  CHECK(decodeError(huge, 4).find("differences") != std::string::npos);
  // A varint that never ends, or runs past 64 bits.
  CHECK(decodeError(threeSteps({0x80}), 4).find("differences") != std::string::npos);
  CHECK(decodeError(threeSteps({0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x02}), 4)
            .find("longer than 64 bits") != std::string::npos);
  CHECK(decodeError(threeSteps({0, 0}), 4).find("1 more than its paths take") != std::string::npos);
}

TEST_CASE("a path blob whose header claims zero robots or steps is rejected") {
  auto blob = encodePaths(twoPaths());
  auto zero_robots = blob;
  zero_robots[8] = zero_robots[9] = 0;
  CHECK(decodeError(zero_robots, 1).find("robot count 0") != std::string::npos);
  auto zero_steps = blob;
  for (int i = 12; i < 16; ++i) zero_steps[static_cast<std::size_t>(i)] = 0;
  CHECK(decodeError(zero_steps, 1).find("zero steps") != std::string::npos);
}

TEST_CASE("a path blob holding a NaN is rejected naming robot, step and coordinate") {
  auto blob = encodePathsV1(twoPaths());
  // Robot 1, step 2, coordinate 1: index (1*4 + 2)*3 + 1 = 19.
  const std::size_t at = kPathBlobHeaderSize + 19 * 8;
  for (int i = 0; i < 8; ++i) blob[at + static_cast<std::size_t>(i)] = 0xff;
  CHECK(decodeError(blob, 9).find("robot 1 step 2 coordinate 1 is not finite") != std::string::npos);
  // Version 2: a keyframe's state, and a difference that lands on infinity
  // (2.0 + (0x7ff0... - 0x4000...) units in the last place).
  auto key = threeSteps({0});
  for (std::size_t i = 0; i < 8; ++i) key[kPathBlobHeaderSize + 12 + 8 + i] = 0xff;
  CHECK(decodeError(key, 9).find("robot 0 step 2 coordinate 0 is not finite") != std::string::npos);
  std::vector<unsigned char> varint;
  std::uint64_t z = 0x7fe0000000000000ull;
  for (; z >= 0x80; z >>= 7) varint.push_back(static_cast<unsigned char>((z & 0x7f) | 0x80));
  varint.push_back(static_cast<unsigned char>(z));
  CHECK(decodeError(threeSteps(varint), 9).find("robot 0 step 1 coordinate 0 is not finite") != std::string::npos);
}

TEST_CASE("encoding refuses paths that no blob can hold") {
  CHECK_THROWS_AS(encodePaths({}), std::invalid_argument);
  auto paths = twoPaths();
  paths[1].push(std::vector<double>{0, 0, 0});  // longer than path 0
  CHECK_THROWS_AS(encodePaths(paths), std::invalid_argument);
  auto nan = twoPaths();
  nan[0].raw()[0] = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(encodePaths(nan), std::invalid_argument);
}

TEST_CASE("a key blob round trips and rejects ragged lengths and infinities") {
  std::vector<double> key{0.5, -1.25, 3e-12};
  auto blob = encodeKey(key);
  CHECK(decodeKey(blob, 1) == key);
  blob.pop_back();
  CHECK_THROWS_AS(decodeKey(blob, 1), CorruptRowError);
  auto inf = encodeKey(std::vector<double>{1.0});
  inf[6] = 0xf0;
  inf[7] = 0x7f;  // +infinity
  CHECK_THROWS_WITH_AS(decodeKey(inf, 11), doctest::Contains("row 11"), CorruptRowError);
}
