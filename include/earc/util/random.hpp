// Seeded randomness that is the same on every standard library: every
// random choice in earc derives from the user's --seed through these.
// (std::uniform_real_distribution's output is implementation-defined, so
// it is not used.)
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>

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

// A stretch {first, first + span} of positions 0..len (len >= 2): span log-uniform
// in [2, len] (short ones straighten a bend, long ones cut a detour), a quarter ending at len.
inline std::pair<std::size_t, std::size_t> drawStretch(std::mt19937_64& rng, std::size_t len) {
  const double span_f = std::exp(uniform(rng, std::log(2.0), std::log(static_cast<double>(len) + 1.0)));
  const std::size_t span = std::clamp<std::size_t>(static_cast<std::size_t>(span_f), 2, len);
  const bool to_goal = uniformIndex(rng, 4) == 0;
  const std::size_t first = to_goal ? len - span : static_cast<std::size_t>(uniformIndex(rng, len - span + 1));
  return {first, first + span};
}

}  // namespace earc
