// The path blob format: header round trip and rejection of corrupt blobs,
// each error naming the row.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

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
  auto paths = twoPaths();
  auto blob = encodePaths(paths);
  CHECK(blob.size() == kPathBlobHeaderSize + 2 * 4 * 3 * 8);
  CHECK(std::string(blob.begin(), blob.begin() + 4) == "EPTH");
  CHECK(decodePaths(blob, 1) == paths);
  PathBlobHeader h = readPathBlobHeader(blob, 1);
  CHECK(h.robots == 2);
  CHECK(h.dim == 3);
  CHECK(h.steps == 4);
}

TEST_CASE("a path blob stores doubles little-endian whatever the host") {
  Path p(1);
  p.push(std::vector<double>{1.0});  // 0x3ff0000000000000
  auto blob = encodePaths({p});
  REQUIRE(blob.size() == kPathBlobHeaderSize + 8);
  CHECK(blob[kPathBlobHeaderSize + 7] == 0x3f);
  CHECK(blob[kPathBlobHeaderSize + 6] == 0xf0);
  CHECK(blob[kPathBlobHeaderSize] == 0x00);
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
  blob[4] = 2;
  auto msg = decodeError(blob, 7);
  CHECK(msg.find("format version 2") != std::string::npos);
  CHECK(msg.find("rebuild") != std::string::npos);
}

TEST_CASE("a path blob with another scalar size is rejected") {
  auto blob = encodePaths(twoPaths());
  blob[6] = 4;
  CHECK(decodeError(blob, 3).find("scalar size 4") != std::string::npos);
}

TEST_CASE("a truncated or overlong path blob is rejected by its length") {
  auto blob = encodePaths(twoPaths());
  auto shorter = std::vector<unsigned char>(blob.begin(), blob.end() - 8);
  CHECK(decodeError(shorter, 5).find("length") != std::string::npos);
  auto longer = blob;
  longer.push_back(0);
  CHECK(decodeError(longer, 5).find("length") != std::string::npos);
  auto header_only = std::vector<unsigned char>(blob.begin(), blob.begin() + 10);
  CHECK(decodeError(header_only, 5).find("too short") != std::string::npos);
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
  auto blob = encodePaths(twoPaths());
  // Robot 1, step 2, coordinate 1: index (1*4 + 2)*3 + 1 = 19.
  const std::size_t at = kPathBlobHeaderSize + 19 * 8;
  for (int i = 0; i < 8; ++i) blob[at + static_cast<std::size_t>(i)] = 0xff;
  auto msg = decodeError(blob, 9);
  CHECK(msg.find("robot 1 step 2 coordinate 1 is not finite") != std::string::npos);
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
