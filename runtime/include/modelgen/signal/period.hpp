// Periodic excitation (Swevers et al. 2002, section 4 and the variance formula after Figure 5):
// the period of a record, and the average of its whole periods with the noise variance of the
// average.
#pragma once

#include <Eigen/Core>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"

namespace modelgen {

/// The period of the positions, in s, from their autocorrelation: the Pearson correlation of
/// the record with itself shifted by a lag (all axes pooled, each weighted by its position
/// variance), computed by FFT for lags up to 3/4 of the record. Past the lobe around lag 0
/// (until the correlation first drops below 0.5), the period is the first lag whose
/// correlation peaks as high as the highest one (at least 0.9), refined to a fraction of a
/// sample by least-squares parabolas through the peaks at every multiple of the period in
/// range (over as few lags as the noise allows). Accuracy on simulated multi-sines: 3e-4
/// sample without noise, 0.01 with noise at 1% of the amplitude, 0.05 with 10%. An excitation
/// generated on the controller's sample clock has a whole number of samples per period;
/// rounding to it before average_periods avoids a misalignment error there when many periods
/// multiply a poor estimate.
/// Works on multi-sines whose fundamental is weak: only the true period brings every harmonic
/// of every axis back into phase. Needs uniform sampling and at least 2 recorded periods.
/// Throws DataError naming the source when the sampling is not uniform, fewer than 8 samples,
/// a value is not finite, the positions do not move, never decorrelate (a drift), never
/// correlate again above 0.9 (no period), or repeat with a period longer than half the record
/// (fewer than 2 periods; the message gives the period and its correlation).
double detect_period(const Trajectory& trajectory);

/// Several periods of a periodic experiment averaged into one (Swevers 2002, section 4).
struct PeriodicAverage {
  /// One period: t (the first N times of the record), q and tau averaged over the periods; dq
  /// and ddq averaged too when the record had them (has_velocity), else zero. N x dof.
  Trajectory averaged;
  /// Per axis, the variance of the noise on the averaged torque ((N m)^2) and position (rad^2):
  /// the sample variance over the periods divided by the number of periods (see
  /// average_periods).
  Eigen::VectorXd tau_noise_variance, q_noise_variance;
  /// Per DFT line l = 0..N/2 (rows) and axis: the noise variance of line l of the averaged
  /// torque and position, E |X_l - X_l,true|^2 with X_l = sum_k x_k exp(-2 pi i l k / N),
  /// from the spread of each period's line about the average: sum_p |D_pl|^2 / (P (P - 1)).
  /// Noise that is not white (a controller's response to the encoder noise, non-periodic
  /// motion) has a colour the per-axis variances above do not show.
  Eigen::MatrixXd tau_line_variance, q_line_variance;
  /// Per DFT line l = 0..N/2 (rows) and axis: the cross-covariance of the noise of line l of
  /// the averaged torque and position, sum_p D_tau,pl conj(D_q,pl) / (P (P - 1)) with the same
  /// deviations as above. Zero in expectation when the errors of q and tau are independent;
  /// a controller that feeds the encoder's error into the torque makes it not (noise_coupling).
  Eigen::MatrixXcd tau_q_line_covariance;
  int periods = 0;                      ///< P, the whole periods averaged
  Eigen::Index samples_per_period = 0;  ///< N = round(period / dt)
  double period = 0;                    ///< N dt, s
  Eigen::Index dropped_samples = 0;     ///< samples after the last whole period, not used
  double dropped_seconds = 0;           ///< dropped_samples * dt
};

/// Averages the P = floor(samples / N) whole periods of a uniformly sampled record, with
/// N = round(period / dt) samples per period; the tail after the last whole period is dropped
/// and reported. The noise variance of the averaged signal, per axis, is
///   sigma^2 = sum_k sum_j (x_j(k) - mean(k))^2 / (N (P - 1)) / P,
/// the unbiased per-sample variance over the periods divided by P. (The formula printed in the
/// paper divides by P (P N - 1) instead, which underestimates the variance by (P - 1) / P.)
/// Throws DataError naming the source for: non-uniform sampling, a period that is not positive
/// and finite, N < 2, a period that is not a whole number of samples (the misalignment it
/// causes over the P periods, |period / dt - N| P, exceeds 0.25 sample), fewer than 2 whole
/// periods, a non-finite q or tau.
PeriodicAverage average_periods(const Trajectory& trajectory, double period);

}  // namespace modelgen
