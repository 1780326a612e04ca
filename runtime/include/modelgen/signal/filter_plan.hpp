// Choosing the position filter's cut-off and the decimation factor for non-periodic data from
// the excitation bandwidth, as Gautier practises it.
#pragma once

#include <string>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"

namespace modelgen {

/// The frequency (Hz) below which `energy_fraction` of the energy of the joint velocities lies,
/// all axes pooled: the excitation bandwidth for plan_filtering. Computed from the positions
/// (measured dq, often filtered by the drive, is not used): per axis q without its
/// least-squares line, Hann-windowed, power spectrum by FFT; the band above fs / 4 is taken as
/// white noise only, and 10 x its mean level (estimated from its median) is subtracted from
/// every line, so that sensor noise and encoder quantization, which differentiation would
/// amplify, do not count; the velocity spectrum is then (2 pi f)^2 times what is left.
/// Coloured errors (timing jitter, data resampled by interpolation) are not removed and raise
/// the estimate: check it, or give the bandwidth to plan_filtering directly.
/// Throws DataError naming the source for non-uniform sampling, fewer than 16 samples,
/// non-finite positions, positions that do not move above their noise; std::invalid_argument
/// for energy_fraction outside (0, 1).
double estimate_bandwidth(const Trajectory& trajectory, double energy_fraction = 0.99);

/// Filtering and decimation settings for non-periodic data. Plain values: a caller may
/// override any of them (e.g. from the command line) before use.
struct FilterPlan {
  double sample_rate_hz = 0;
  double bandwidth_hz = 0;        ///< excitation bandwidth the plan was made for
  double position_cutoff_hz = 0;  ///< filter_positions cut-off
  int position_order = 4;         ///< filter_positions Butterworth order
  int decimation_factor = 1;      ///< n_d of decimate
  /// 0.8 (fs / 2) / n_d, the decimation filter's cut-off (no filter is applied for n_d = 1)
  double decimation_cutoff_hz = 0;
  std::string explanation;  ///< one line saying what was chosen and why
};

/// Gautier's practice, as a rule: the position filter must not touch the dynamics, so its
/// cut-off is 10 x the bandwidth (at most 0.8 x Nyquist); the decimation keeps the identified
/// frequency range, so n_d is the largest factor whose decimation filter cut-off,
/// 0.8 (fs / 2) / n_d, is still at least 2 x the bandwidth (n_d = 1 when none is).
/// Throws std::invalid_argument for a sample rate <= 0 or a bandwidth not in (0, fs / 2).
FilterPlan plan_filtering(double sample_rate_hz, double bandwidth_hz);

}  // namespace modelgen
