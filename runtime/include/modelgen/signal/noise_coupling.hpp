// Whether the errors of the positions and the torques of a periodic record are independent, as
// errors in variables (Bona & Curatella eq. 16) takes them: a test on the coherence of their
// period-to-period deviations. A controller feeds the encoder's error into the torque command,
// so a closed-loop record fails it even without its reference columns.
#pragma once

#include <Eigen/Core>

#include "modelgen/signal/period.hpp"

namespace modelgen {

/// Per axis (dof values each): how much of the torque's period-to-period deviation follows
/// the position's, and how sure that is.
struct NoiseCoupling {
  /// The fraction of the torque deviations' energy a linear response to the position
  /// deviations explains (a transfer function free in each band of lines: any controller),
  /// corrected for its bias under independence (1 / K per band) and square-rooted: a
  /// correlation, 0 when independent, 1 when the torque's deviations are all response.
  Eigen::VectorXd correlation;
  /// The independence test's statistic as a standard normal score (Wilson-Hilferty from the
  /// chi-square below): about N(0, 1) when the errors are independent, large when not.
  Eigen::VectorXd z;
  /// Fisher's combination of the bands' coherences, sum_b -2 (K - 1) log(1 - gamma_b^2),
  /// chi-square with 2 `bands` degrees of freedom under independence.
  Eigen::VectorXd chi_square;
  Eigen::VectorXi bands;   ///< bands with noise on both sides, per axis
  int lines_per_band = 0;  ///< B
  int degrees = 0;         ///< K = B (P - 1), complex degrees of freedom per band
  bool empty() const { return z.size() == 0; }
};

/// The coupling test on the line spreads of `average` (q_line_variance, tau_line_variance,
/// tau_q_line_covariance).
///
/// Why lines. The deviations of P periods from their mean have P - 1 degrees of freedom per
/// sample, but neighbouring samples are not independent (a filter, a decimation, the
/// controller's own dynamics colour the noise), so a sample correlation has no known
/// distribution. The DFT lines of stationary noise over a period are, to a good approximation,
/// independent complex Gaussians whatever the colour: each line of each period gives one
/// complex degree of freedom (P - 1 per line after the mean). Lines 1..(N-1)/2 (not the
/// constant, not Nyquist) are grouped in bands of B = ceil(16 / (P - 1)) neighbours, over
/// which the noise's spectrum and a controller's response are about constant; a band's
/// coherence gamma_b^2 = |sum C_l|^2 / (sum V_tau,l sum V_q,l) then follows Beta(1, K - 1)
/// under independence (K = B (P - 1)), so (1 - gamma_b^2)^(K - 1) is uniform and Fisher's sum
/// above is chi-square with 2 degrees per band. Bands where either side has no noise at all
/// (exact positions, below 1e-12 of their largest value per sample; a filter's stop band,
/// below 1e-20 of the largest band) carry no information and are left out.
/// Needs P >= 2 and N >= 2 B + 2 lines; returns an empty NoiseCoupling otherwise.
NoiseCoupling noise_coupling(const PeriodicAverage& average);

}  // namespace modelgen
