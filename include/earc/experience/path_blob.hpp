// The on-disk form of an experience's paths and key.
//
// Path blob: a 16-byte header, then the paths, robot after robot:
//   offset 0  4 bytes  magic "EPTH"
//   offset 4  u16      format version (1, 2 or 3; written: kPathBlobVersion)
//   offset 6  u8       scalar size in bytes (8)
//   offset 7  u8       flags (0; reserved)
//   offset 8  u16      robot count
//   offset 10 u16      per-robot dimension
//   offset 12 u32      steps (states per robot; all robots alike)
// Version 1 body: every state's little-endian IEEE-754 doubles, robot-major
// (robot r, step t, coordinate d).
// Version 2 body, per robot (lossless, about a fifth of version 1 for the
// builder's mobile paths, which are mostly straight runs):
//   u32 K                 keyframes, 1..steps
//   K x u32               their steps: 0 first, steps - 1 last, increasing
//   K x dim doubles       their states
//   varints               every other state, step by step, coordinate by
//                         coordinate: the zigzag-coded difference between
//                         its IEEE bit pattern and that of the straight-line
//                         estimate between the keyframes around it
//                         (keyframeEstimate), usually 0 or 1 (one byte).
// Version 3 body: version 2's, then a u32 CRC-32C (Castagnoli) of every
// byte before it, header included. SQLite checks its pages' structure,
// not their contents: without it a flipped bit in a stored path read back
// as another path.
// Written from schema version 6 on (migrations/0006_path_blob_checksums.sql).
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
inline constexpr std::uint16_t kPathBlobVersion = 3;  // written; 1 and 2 are still read
inline constexpr std::size_t kPathBlobHeaderSize = 16;
inline constexpr int kMaxBlobRobots = 64;
inline constexpr int kMaxBlobDim = 64;

struct PathBlobHeader {
  int version = 0;
  int robots = 0;
  int dim = 0;
  std::size_t steps = 0;
};
// Checks the header's fields (not the blob's length). Throws CorruptRowError.
PathBlobHeader readPathBlobHeader(std::span<const unsigned char> blob, std::int64_t row);

// Version 3; decodePaths gives back exactly these doubles. Throws
// std::invalid_argument for paths that cannot be stored: none, empty,
// different lengths or dimensions, non-finite numbers.
std::vector<unsigned char> encodePaths(const std::vector<Path>& paths);
// Versions 1 and 2, for tests and tools that need an old blob.
std::vector<unsigned char> encodePathsV1(const std::vector<Path>& paths);
std::vector<unsigned char> encodePathsV2(const std::vector<Path>& paths);

// The CRC-32C (Castagnoli, reflected; iSCSI's, ext4's) of `bytes`: by
// SSE 4.2's crc32 instruction where the processor has it, else by tables
// (crc32cPortable, the same value).
std::uint32_t crc32c(std::span<const unsigned char> bytes);
std::uint32_t crc32cPortable(std::span<const unsigned char> bytes);

// The straight-line estimate of coordinate values a (at step i) and b (at
// step j) at step t, i < t < j, that version 2 stores differences from.
// Its rounding is fixed by IEEE-754 whatever the compiler contracts.
double keyframeEstimate(double a, double b, std::size_t i, std::size_t j, std::size_t t);
// Throws CorruptRowError(row, reason).
std::vector<Path> decodePaths(std::span<const unsigned char> blob, std::int64_t row);

std::vector<unsigned char> encodeKey(std::span<const double> key);
// Throws CorruptRowError(row, reason) for a length that is not a whole
// number of doubles or a non-finite value.
std::vector<double> decodeKey(std::span<const unsigned char> blob, std::int64_t row);

}  // namespace earc::exp
