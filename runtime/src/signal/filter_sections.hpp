// How a LowPassFilter runs over a buffer: the cascade of sections in transposed direct form II,
// its start in steady state, and the odd-reflection padding of zero-phase filtering, shared by
// filtfilt and decimate.
#pragma once

#include <algorithm>
#include <vector>

#include <Eigen/Core>

#include "modelgen/signal/lowpass.hpp"

namespace modelgen::detail {

/// Samples over which the slowest pole decays by e^-10: how long a start-up transient lasts.
Eigen::Index settling_samples(const LowPassFilter& filter);

/// One pass of the cascade over u[0..len) (backward: from the end), transposed direct form II.
/// It starts in the steady state of the ramp through its first two values, as if the input had
/// always been that ramp: a unit-DC-gain section answers v0 + d k with v0 + d (k - D), D its DC
/// delay, and its two states then hold what the past of that ramp left in them. A linear input
/// passes without any start-up transient. `state` is scratch.
void run_sections(const LowPassFilter& filter, double* u, Eigen::Index len, bool backward,
                  std::vector<double>& state);

/// Zero-phase filtering of one column (any stride) into `buffer` (odd-reflection padded, see
/// filtfilt); returns the offset of the first original sample in the buffer.
template <typename Column>
Eigen::Index filtfilt_column(const LowPassFilter& filter, const Column& x, Eigen::Index settling,
                             std::vector<double>& buffer, std::vector<double>& state) {
  const Eigen::Index n = x.size();
  const Eigen::Index pad = std::min(n - 1, settling);
  buffer.resize(n + 2 * pad);
  double* u = buffer.data();
  for (Eigen::Index k = 0; k < n; ++k) u[pad + k] = x(k);
  for (Eigen::Index i = 1; i <= pad; ++i) {
    u[pad - i] = 2.0 * x(0) - x(i);
    u[pad + n - 1 + i] = 2.0 * x(n - 1) - x(n - 1 - i);
  }
  const auto len = static_cast<Eigen::Index>(buffer.size());
  run_sections(filter, u, len, false, state);
  run_sections(filter, u, len, true, state);
  return pad;
}

}  // namespace modelgen::detail
