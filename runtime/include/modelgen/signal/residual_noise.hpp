// Is a fit's residual what the record's noise leaves? Per joint, the residual's energy in the
// excitation band against the noise estimated there (modelgen/signal/noise_floor.hpp), with
// the bounds a right model stays within given both figures' degrees of freedom (issue 31).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/signal/noise_floor.hpp"

namespace modelgen {

/// The one-sided standard normal point the bounds use: 3.29, a tail of 0.05 % on each side.
inline constexpr double kResidualCheckZ = 3.2905;

/// The point of chi-square with `dof` degrees of freedom at standard normal point `z`
/// (Wilson-Hilferty: (X / dof)^(1/3) is nearly normal, mean 1 - 2 / (9 dof), variance
/// 2 / (9 dof)); 0 where the approximation would go negative.
double chi_square_point(double z, double dof);

/// One record as a fit compared it: measured torques and their error (samples x axes, the
/// same rows), sampled every `dt` s, and its excitation band.
struct ResidualRecord {
  Eigen::MatrixXd tau, error;
  double dt = 0;
  ExcitationBand band;
};

/// One joint's residual in the band against its noise there, the records pooled.
struct JointResidual {
  double residual = 0;  ///< energy of the error in the band, (N m)^2 summed over samples
  double torque = 0;    ///< energy of the measured torque in the band
  double noise = std::numeric_limits<double>::quiet_NaN();  ///< noise energy there; NaN: none
  double residual_dof = 0, noise_dof = 0;                   ///< degrees of freedom of each
  double ratio = std::numeric_limits<double>::quiet_NaN();  ///< residual / noise
  /// A right model's ratio lies within [lower, upper] but for 0.05 % on each side.
  double lower = 0, upper = std::numeric_limits<double>::infinity();
  double in_band_lines = 0;  ///< frequency lines in the band, records summed
  std::string noise_origin;  ///< of the first record
};

/// Per joint (column) of `records` (at least one; every record with the same columns): the
/// residual's and the noise's energies in the band (band_energies of the column) and their
/// bounds. Degrees of freedom, per record of L = band_hz n dt lines in the band:
/// - the residual's energy sums L windowed lines of 2 each, halved for the Hann window's
///   correlation of neighbouring lines: L;
/// - the noise from P periods' changes: the same over the P - 1 periods of differences,
///   L (P - 1) / P;
/// - the noise from the lower quartile of L line powers: the sample quartile of exponential
///   powers has a relative variance of (1/3) / (L ln^2(4/3)) = 4.0 / L, doubled for the
///   window: chi-square's 2 / dof gives L / 4.
/// The ratio of a right model is (chi2(nu_r) / nu_r) / (chi2(nu_n) / nu_n), so
/// upper = chi2_{+z}(nu_r) / nu_r / (chi2_{-z}(nu_n) / nu_n) and lower the other way round
/// (z = kResidualCheckZ); the p parameters of the fit take p / (2 L dof) of the in-band
/// residual on average, which stays within `lower` unless rows per parameter are few: that
/// is what a ratio below `lower` says. A joint whose noise could not be estimated (too few
/// lines) keeps a NaN ratio.
std::vector<JointResidual> residual_against_noise(const std::vector<ResidualRecord>& records);

/// One averaged period as a fit compared it (the periodic route, --periodic): measured torques
/// and their error (N samples x axes, one whole period), and the noise of the averaged torque
/// from the spread of the P periods about their average (PeriodicAverage): per axis the
/// variances E|E_l|^2 of its DFT lines l = 0.. (`lines`, rows: lines, columns: axes; the
/// torques cut at the last of them), or, when `lines` is empty, white noise of per-sample
/// variance `white` per axis.
struct PeriodRecord {
  Eigen::MatrixXd tau, error;
  Eigen::MatrixXd lines;
  Eigen::VectorXd white;
  int periods = 0;  ///< P
  int band = 0;     ///< the band's last harmonic (kTorqueBandFactor times the motion's)
};

/// Per joint, the averaged periods' residual in harmonics 0..band (and below the torques' cut)
/// against the noise the period-to-period spread leaves there, pooled over `records` (at
/// least one, the same axes). Over one period the DFT has no leakage: the residual's energy in
/// L + 1 lines is (|R_0|^2 + 2 sum_{l=1..L} |R_l|^2) / N, its noise's the same of E|E_l|^2
/// (or (2 L + 1) `white` for white noise), with 2 L + 1 and (2 L + 1) (P - 1) degrees of freedom
/// (each line's variance comes from P - 1 independent deviations); the bounds as in
/// residual_against_noise. The noise of the averaged positions that the regressor carries into
/// the residual is not counted (a fraction of the torque's where the positions' noise is small
/// against their motion). A record with P < 2 or no line in the band keeps a NaN ratio.
std::vector<JointResidual> period_residual_against_noise(const std::vector<PeriodRecord>& records);

}  // namespace modelgen
