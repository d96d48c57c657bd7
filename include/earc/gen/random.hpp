// Random numbers for scenario generation that are the same everywhere.
//
// std::mt19937_64's output sequence is fixed by the C++ standard, but the
// standard distributions (std::uniform_real_distribution, ...) are not: two
// standard libraries turn the same engine output into different numbers. So
// the conversions from engine output to numbers live here, and one seed
// gives one scenario with every compiler and library.
#pragma once

#include <cstdint>
#include <random>

namespace earc::gen {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1): the top 53 bits of one engine output.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace earc::gen
