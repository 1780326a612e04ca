// The noise on the prepared period of the periodic route (averaged, Fourier-projected positions
// with analytic derivatives, averaged torques), per axis, for errors in variables (Bona &
// Curatella eq. 13-16 need the covariance of every observed variable).
#pragma once

#include <Eigen/Core>

#include "modelgen/signal/noise_coupling.hpp"
#include "modelgen/signal/period.hpp"

namespace modelgen {

/// Per axis (dof values each): noise variances of q, dq, ddq (rad^2, (rad/s)^2, (rad/s^2)^2)
/// and tau ((N m)^2) of one sample of the prepared period, averaged over the period, and the
/// covariance of the q and ddq noise (rad^2/s^2, negative). Empty vectors: not known (the data
/// were not prepared by the periodic route).
struct PeriodicNoise {
  Eigen::VectorXd q, dq, ddq, tau, q_ddq;
  /// The lines the variances above come from, for covariances of sums over the period (the
  /// noise is correlated from sample to sample): E|E_l|^2 of the averaged positions for
  /// l = 0..H (rows; columns: axes), and of the averaged torques for l = 0..H_tau, empty when
  /// the torques are kept whole (then white with variance `tau`).
  Eigen::MatrixXd q_lines, tau_lines;
  Eigen::Index samples = 0;  ///< N, samples of the period
  double period = 0;         ///< s
  int periods = 0;           ///< P, the periods averaged (the variances' P - 1 degrees of freedom)
  /// Whether the errors of q and tau are independent, as the variances above take them
  /// (noise_coupling of the same average; filled by prepare_experiment's periodic route).
  NoiseCoupling coupling;
  bool empty() const { return q.size() == 0; }
};

/// The noise of the series that keeps harmonics 0..`harmonics` of the averaged positions
/// (fit_fourier, apply_fourier), and of the averaged torques kept up to `torque_harmonics`
/// (keep_harmonics; a negative value: kept whole, every sample as averaged).
///
/// Derivation. The averaged x_k = x_true,k + e_k, k = 0..N-1, has DFT lines
/// X_l = sum_k x_k exp(-2 pi i l k / N) whose noise E_l has E|E_l|^2 = v_l
/// (PeriodicAverage::q_line_variance). The series is
///   x(t) = (1/N) [X_0 + 2 Re sum_{l=1..H} X_l exp(i w l (t - t_0))],  w = 2 pi / period,
///   dx/dt = (2/N) Re sum_l (i w l) X_l exp(...),  d2x/dt2 = -(2/N) Re sum_l (w l)^2 X_l exp(...).
/// Noise lines of white or stationary noise are uncorrelated between lines, and a line's real
/// and imaginary parts have equal variance v_l / 2 and no correlation (the phase of the
/// noise is uniform), so over a period E[(2 Re(E_l z))^2] = 2 v_l for any |z| = 1 and
///   var q   = (v_0 + 2 sum_l v_l) / N^2,
///   var dq  = 2 sum_l (w l)^2 v_l / N^2,
///   var ddq = 2 sum_l (w l)^4 v_l / N^2,
///   cov(q, ddq) = -2 sum_l (w l)^2 v_l / N^2,   cov(q, dq) = cov(dq, ddq) = 0
/// (Re(z) and Re(i z) are uncorrelated for such a line). The torque's variance is the same sum
/// over its kept lines, or tau_noise_variance when it is kept whole. Neglected: the
/// correlation between axes and between q and tau (a closed loop makes the torque noise
/// respond to the position noise), and between samples (the series has 2 H + 1 degrees of
/// freedom per period, not N).
PeriodicNoise periodic_noise(const PeriodicAverage& average, int harmonics, int torque_harmonics);

}  // namespace modelgen
