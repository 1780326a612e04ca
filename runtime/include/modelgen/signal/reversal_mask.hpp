// Which torque equations of a record the Coulomb model sign(v) describes: not those near a
// joint's (or a coupled motor's) reversal. Applied before the parallel decimation (Gautier &
// Briot eq. 13-14): an equation tau = W beta weighted on both sides still holds, so the linear
// decimation filter keeps the decimated equations exact; leaving out decimated rows instead
// keeps, inside each row's filter window, the samples near rest it was meant to drop (issue 31:
// on a noise-free closed-loop TX-40 record, exact states with sign friction left Ia5 +7.9 %
// through the decimation, weighted 0.0 %).
#pragma once

#include <Eigen/Core>

namespace modelgen {

/// Samples x dof of weights in [0, 1] for the torque equations (both sides). Equation j is
/// weighted 0 at a sample where joint j or a motor m whose velocity enters it (K(m, j) != 0, K
/// the drive chain's motor_from_joint) is slower than min_speed: joint j by |dq_j|, motor m by
/// |K.row(m) dq / K(m, m)| (its speed on its joint's scale, as the coupled-motor friction Fcm
/// is written). Near rest a joint sticks while its friction is anything between -Fc and Fc,
/// and the prepared velocity's sign there is only an estimate. At d samples from the nearest
/// such sample the weight rises as 0.5 - 0.5 cos(pi d / (guard + 1)) and is 1 beyond `guard`:
/// a smooth weight, because the torques hold the loop's motion above the position filter's
/// cut-off that the prepared regressor lacks, and a weight with steps would carry it into the
/// kept band (measured on the bundled COMAU record: a 0/1 weight over one cut-off period left
/// 14 of 64 parameters beyond 3 sd, this ramp over two none). Empty min_speed: all 1.
/// Throws std::invalid_argument for sizes that disagree or a negative guard.
Eigen::ArrayXXd reversal_mask(const Eigen::MatrixXd& dq, const Eigen::MatrixXd& K,
                              const Eigen::VectorXd& min_speed, Eigen::Index guard);

/// The guard of reversal_mask for positions low-passed at `cutoff_hz` (zero phase): two periods
/// of the cut-off, in samples at `sample_rate_hz`, so that the ramp's spectrum lies below the
/// cut-off (its first zero at 0.75 of it) while the filter's impulse response, which spreads
/// the velocity's error at a reversal, fits inside. 0 for cutoff_hz <= 0 (no filter).
Eigen::Index reversal_guard_samples(double cutoff_hz, double sample_rate_hz);

}  // namespace modelgen
