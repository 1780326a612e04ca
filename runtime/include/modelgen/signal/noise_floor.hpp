// The part of a measured torque no model of the excitation can explain: its energy above the
// excitation band (a closed loop's response to encoder noise sits there) and the noise inside
// the band, so that a prediction's error is judged in the band and against the record's own
// floor (issue 31; Bona & Curatella section 3.4: the content above the band is noise).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"

namespace modelgen {

/// The band the torques of an excitation occupy: the motion's band times this factor. The
/// torques hold products of two motion terms (dq^2, ddq times cos q), whose band reaches twice
/// the motion's.
constexpr double kTorqueBandFactor = 2.0;

/// Above this fraction of the measured torque's energy outside the band, the relative error in
/// the band is the figure that says how good a model is (the full-band one mostly measures
/// the out-of-band noise).
constexpr double kOutOfBandDominates = 0.5;

/// The excitation band a comparison is judged in.
struct ExcitationBand {
  double band_hz = 0;  ///< upper edge, Hz: the band is 0..band_hz
  double period = 0;   ///< s, the excitation's period when known, else 0
  std::string origin;  ///< how the band was found, for the user
};

/// kTorqueBandFactor times the highest harmonic with a non-zero coefficient over its period;
/// the period is the series'. Throws DataError naming `source` when no coefficient is non-zero.
ExcitationBand band_of_fourier(const FourierTrajectory& fourier, const std::string& source);

/// kTorqueBandFactor times the band of the joint velocities (estimate_bands(positions)
/// .velocity_hz, from the positions only, torques ignored), and the period of the positions
/// when detect_period finds one (0 otherwise). Throws DataError (naming the source) as
/// estimate_bands does: non-uniform sampling, fewer than 16 samples, positions that do not move.
ExcitationBand band_of_positions(const Trajectory& positions);

/// Energies (sums of squares over samples and axes, (N m)^2) of one record's measured torque
/// and of the error of a prediction of it, split at the band.
struct BandEnergies {
  ExcitationBand band;
  long long values = 0;                 ///< samples x axes
  double torque = 0, torque_above = 0;  ///< measured torque: all of it, above the band
  double error = 0, error_above = 0;    ///< measured minus predicted: all, above the band
  /// The noise energy of the error inside the band; NaN when it could not be estimated.
  double noise_in_band = std::numeric_limits<double>::quiet_NaN();
  std::string noise_origin;  ///< how noise_in_band was estimated, or why not
  /// The periods whose changes gave noise_in_band; 0 when it came from the quartile (or none).
  long long noise_periods = 0;
};

/// Splits the energies of `tau` and `error` (samples x axes, uniformly sampled every `dt` s)
/// at band.band_hz: per column, its energy times the share of its Hann-windowed power spectrum
/// at or below the band's edge (the window keeps content far above the band, and the jump
/// between the record's ends, out of the band's lines). The noise of the error in the band:
/// - periodic (band.period > 0, at least 2 whole periods of round(period / dt) samples that
///   stay aligned within 0.25 sample, and at least 4 lines in the band): from the differences
///   between consecutive periods, e(t + period) - e(t), in which what repeats (the excitation,
///   whatever a model of it explains) cancels and the noise is left, with twice its power on
///   average over a band of whole harmonics: half their energy in the band, scaled to the record's
///   length;
/// - otherwise: the lower quartile of the error's windowed line powers in the band, divided by
///   -ln(0.75) (the quartile of exponentially distributed noise powers), over every line of the
///   band; it assumes most lines of the band hold noise only.
/// Throws std::invalid_argument for matrices of different shapes or dt <= 0.
BandEnergies band_energies(const Eigen::MatrixXd& tau, const Eigen::MatrixXd& error, double dt,
                           const ExcitationBand& band);

/// The comparison of one or several records (their energies pooled).
struct NoiseFloor {
  double full_band = 0;             ///< ||error|| / ||tau||
  double in_band = 0;               ///< the same of the parts in the band
  double out_of_band_fraction = 0;  ///< of the measured torque's energy, above the band
  /// sqrt(noise in the band / torque energy in the band): the in-band relative error a model
  /// that explains everything but the noise would get; NaN when not estimated.
  double floor = std::numeric_limits<double>::quiet_NaN();
  /// The rms over samples and axes of the error's part in the band and of the noise there
  /// (N m; NaN when not estimated): the floor in absolute terms.
  double in_band_rms = 0, floor_rms = std::numeric_limits<double>::quiet_NaN();
  /// out_of_band_fraction > kOutOfBandDominates: in_band is the headline figure.
  bool in_band_headline = false;
};

/// Pools `records` (at least one). NaN figures where a torque energy is zero.
NoiseFloor noise_floor(const std::vector<BandEnergies>& records);

}  // namespace modelgen
