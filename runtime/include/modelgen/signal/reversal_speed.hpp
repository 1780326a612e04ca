// The minimum speed of the reversal weighting (reversal_mask) chosen from a record: the speed
// below which the prepared velocity's sign is not to be trusted (issue 31).
#pragma once

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"

namespace modelgen {

/// Per joint, the speeds that make up reversal_min_speed's choice (rad/s or m/s).
struct ReversalSpeed {
  /// Below it the sign of the prepared velocity is unreliable: max(noise, lag) where the noise
  /// flips it over more than a sample per reversal (noise > step), else lag.
  Eigen::VectorXd speed;
  /// The median step |dq_s+1 - dq_s| of the prepared velocity across its sign changes (|ddq|
  /// dt at a reversal); infinite for a joint that does not reverse.
  Eigen::VectorXd step;
  /// 3 sigma_v: sigma_v = sigma_q sqrt(sum_k g_k^2), g the impulse response of the position
  /// filter followed by the central difference (per second), sigma_q position_noise_std.
  Eigen::VectorXd noise;
  /// The largest |dq| where the prepared velocity is off by more than half of itself beyond 3
  /// noise sigma of a reference velocity from the same positions filtered at kReferenceBand
  /// times the cut-off: a sign the reference contradicts, a joint at rest by it, or (on a real
  /// record with motion above the cut-off) the same sign half off. 0 on clean reversals.
  Eigen::VectorXd lag;
  /// Samples whose sign was compared (the reference reliable there).
  Eigen::Index compared = 0;
};

/// The reference's cut-off in multiples of the position filter's: its impulse response is this
/// many times shorter, so it follows a joint's stop and start that the position filter spreads.
inline constexpr double kReferenceBand = 4.0;

/// Velocity noise std per unit position noise std of positions low-passed at `cutoff_hz`
/// (zero phase, Butterworth `order`) and differentiated by central differences at
/// `sample_rate_hz`: sqrt(sum_k g_k^2) from the filter's impulse response, 1/s.
double velocity_noise_gain(double cutoff_hz, int order, double sample_rate_hz);

/// The minimum speed per joint for `raw` (uniform time grid, unfiltered positions) prepared
/// with a position filter at `cutoff_hz` of `order`; `q_noise_std` the positions' noise std per
/// joint (position_noise_std). The first and last `edge` samples of the prepared record (the
/// filter's edges) are not compared. Empty when the record is shorter than 2 edge + 3 samples.
ReversalSpeed reversal_min_speed(const Trajectory& raw, double cutoff_hz, int order,
                                 const Eigen::VectorXd& q_noise_std, Eigen::Index edge);

}  // namespace modelgen
