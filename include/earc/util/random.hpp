// Seeded randomness that is the same on every standard library: every
// random choice in earc derives from the user's --seed through these.
// (std::uniform_real_distribution's output is implementation-defined, so
// it is not used.)
#pragma once

#include <cstdint>
#include <random>

namespace earc {

// A well-mixed child seed for stream `stream` of `seed` (splitmix64).
inline std::uint64_t splitSeed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Uniform double in [lo, hi).
inline double uniform(std::mt19937_64& rng, double lo, double hi) {
  double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return lo + (hi - lo) * u;
}

// Uniform integer in [0, n).
inline std::uint64_t uniformIndex(std::mt19937_64& rng, std::uint64_t n) {
  return n == 0 ? 0 : rng() % n;
}

}  // namespace earc
