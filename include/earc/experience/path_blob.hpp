// The on-disk form of an experience's paths and key.
//
// Path blob: a 16-byte header, then little-endian IEEE-754 doubles,
// robot-major (robot r, step t, coordinate d):
//   offset 0  4 bytes  magic "EPTH"
//   offset 4  u16      format version (kPathBlobVersion)
//   offset 6  u8       scalar size in bytes (8)
//   offset 7  u8       flags (0; reserved)
//   offset 8  u16      robot count
//   offset 10 u16      per-robot dimension
//   offset 12 u32      steps (states per robot; all robots alike)
// Decoding checks every header field, the exact length, and that every
// number is finite, and names the row on error (like nanoflann's saved
// index: a mismatch tells the user what to do, never reads garbage).
//
// Key blob: little-endian doubles, no header (the class fixes its length).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "earc/scene/path.hpp"

namespace earc::exp {

inline constexpr unsigned char kPathBlobMagic[4] = {'E', 'P', 'T', 'H'};
inline constexpr std::uint16_t kPathBlobVersion = 1;
inline constexpr std::size_t kPathBlobHeaderSize = 16;
inline constexpr int kMaxBlobRobots = 64;
inline constexpr int kMaxBlobDim = 64;

struct PathBlobHeader {
  int robots = 0;
  int dim = 0;
  std::size_t steps = 0;
  std::size_t expectedSize() const { return kPathBlobHeaderSize + 8 * static_cast<std::size_t>(robots * dim) * steps; }
};
// Checks the header's fields (not the blob's length). Throws CorruptRowError.
PathBlobHeader readPathBlobHeader(std::span<const unsigned char> blob, std::int64_t row);

// Throws std::invalid_argument for paths that cannot be stored: none, empty,
// different lengths or dimensions, non-finite numbers.
std::vector<unsigned char> encodePaths(const std::vector<Path>& paths);
// Throws CorruptRowError(row, reason).
std::vector<Path> decodePaths(std::span<const unsigned char> blob, std::int64_t row);

std::vector<unsigned char> encodeKey(std::span<const double> key);
// Throws CorruptRowError(row, reason) for a length that is not a whole
// number of doubles or a non-finite value.
std::vector<double> decodeKey(std::span<const unsigned char> blob, std::int64_t row);

}  // namespace earc::exp
