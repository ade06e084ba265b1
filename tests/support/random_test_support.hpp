// Seeded random numbers for tests: the same draws on every platform and standard library.
#pragma once

#include <cstdint>
#include <random>

namespace talus::random_test {

/// A uniform draw in [lo, hi) from the top 53 bits of one mt19937_64 output. Unlike
/// std::uniform_real_distribution, whose algorithm the standard leaves open, this gives the same
/// sequence everywhere, so seeded tests see the same cases on every machine.
inline double uniform(std::mt19937_64& rng, double lo = 0.0, double hi = 1.0) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

}  // namespace talus::random_test
