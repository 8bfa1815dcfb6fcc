// Numbers drawn from a std::mt19937_64 stream without the standard distributions: their
// algorithms are implementation-defined, so the same seed would give other numbers with another
// standard library. mt19937_64's raw output is fixed by the standard; these draws use it alone.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>

namespace claspplan {

/// Uniform in [0, 1) from the top 53 bits of one raw draw.
inline double uniform01(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

/// Uniform index in [0, n) from one raw draw (n > 0; the bias is below n / 2^53).
inline std::size_t uniform_index(std::uint64_t bits, std::size_t n) {
  return std::min(static_cast<std::size_t>(uniform01(bits) * static_cast<double>(n)), n - 1);
}

/// Standard normal by the Box-Muller transform; takes two raw draws.
inline double standard_normal(std::mt19937_64& rng) {
  const double u1 = 1.0 - uniform01(rng());  // in (0, 1]: the logarithm stays finite
  const double u2 = uniform01(rng());
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

}  // namespace claspplan
