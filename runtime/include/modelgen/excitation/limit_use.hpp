// How much of each joint limit a periodic excitation uses: its extreme position, speed and
// acceleration on a dense grid over one period, compared with the description's limits. The
// series is evaluated analytically (Swevers eq. 15-17), so the grid, not the output sample
// time, decides what is seen between samples.
#pragma once

#include <string>
#include <vector>

#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen {

/// The extremes of one joint over one period, with the times they occur.
struct JointExtremes {
  double q_min = 0, q_min_time = 0, q_max = 0, q_max_time = 0;
  double dq_peak = 0, dq_time = 0;    ///< max |dq|
  double ddq_peak = 0, ddq_time = 0;  ///< max |ddq|
};

/// Grid points per period: `rate` (Hz) times the period, and at least 1000 per period of the
/// highest harmonic L, so a peak is missed by less than (pi/1000)^2 / 2 = 5e-6 of its amplitude;
/// rounded up to a multiple of the power of two >= L (fewer than 2 L points more) when the count
/// has no divisor of the form 2^a 3^b 5^c near L, for the FFT evaluation of the grid.
long limit_grid_points(const FourierTrajectory& trajectory, double rate = 1000.0);

/// The extremes of every joint of `trajectory` on limit_grid_points(trajectory, rate) points of
/// one period (the series is periodic: one period holds every value it takes), each at the
/// first grid point that reaches it (equal peaks: the earliest), its value from evaluate().
/// The cost is O(n log L) for n points and L harmonics, not O(n L).
std::vector<JointExtremes> trajectory_extremes(const FourierTrajectory& trajectory,
                                               double rate = 1000.0);

/// One limit key ("q", "dq", "ddq") of one joint: the peak value, its limit and the fraction
/// of the limit used. Positions: the distance from the middle of [lower, upper] over half
/// the range, so 1 is on a limit and a margin shrinks the range about its middle; the value
/// is the extreme position on the side used most and `limit` that side's limit.
struct LimitUse {
  int joint = 0;  ///< 0-based
  std::string key;
  double value = 0, limit = 0, time = 0, use = 0;
};

/// The use of every limit `limits` (one per joint) gives, in joint then key order; keys
/// a joint has no limit for are left out (missing_limits names them).
std::vector<LimitUse> limit_uses(const std::vector<JointExtremes>& extremes,
                                 const std::vector<JointLimits>& limits);

/// The limit keys (q, dq, ddq) each joint lacks, as (joint 0-based, key).
std::vector<std::pair<int, std::string>> missing_limits(const std::vector<JointLimits>& limits);

}  // namespace modelgen
