// Seeded Gaussian noise for simulated measurements: the same seed gives the same numbers on
// every platform (std::normal_distribution's algorithm is the library's choice; this is not).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace modelgen {

/// Standard normal numbers by Box-Muller on std::mt19937_64 (whose sequence the standard
/// fixes), one cosine branch per call.
class GaussianNoise {
 public:
  explicit GaussianNoise(std::uint64_t seed) : engine_(seed) {}

  double operator()() {
    const double u1 = uniform(), u2 = uniform();  // named: operand order is unspecified
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  // In (0, 1): 53 random bits, centred, so log() never sees 0.
  double uniform() { return (static_cast<double>(engine_() >> 11) + 0.5) * 0x1.0p-53; }

  std::mt19937_64 engine_;
};

}  // namespace modelgen
