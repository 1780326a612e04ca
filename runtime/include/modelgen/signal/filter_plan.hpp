// Choosing the position filter's cut-off and the decimation factor for non-periodic data from
// the excitation bandwidth, as Gautier practises it.
#pragma once

#include <string>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"

namespace modelgen {

/// The bands of an experiment's excitation (Hz), as estimate_bands finds them.
struct ExcitationBands {
  double velocity_hz = 0;  ///< below it, energy_fraction of the joint velocities' energy
  double torque_hz = 0;    ///< below it, energy_fraction of the torques' energy (0: none)
  double bandwidth_hz = 0;  ///< the larger: the band identification must keep
};

/// The excitation bandwidth for plan_filtering: the larger of two bands, all axes pooled.
/// - Motion: the frequency below which `energy_fraction` of the energy of the joint velocities
///   lies, computed from the positions (measured dq, often filtered by the drive, is not used).
/// - Torques (when the trajectory has measured ones): the frequency below which
///   `energy_fraction` of the torques' energy lies. The dynamics are nonlinear in the motion
///   and hold friction, so the torques, and the regressor with them, reach above the motion's
///   band; the decimation must keep both sides of tau = W beta (Gautier & Briot eq. 13-14).
/// Per axis the signal has its least-squares line removed, is Hann-windowed and its power
/// spectrum taken by FFT; only lines standing out of the noise count: a line counts when it
/// exceeds 20 times the local mean noise power (noise alone would do so with probability
/// exp(-20) = 2e-9), the floor being estimated per quarter octave (at least 64 lines) from the
/// 10% quantile of the lines around it, so that coloured noise (timing jitter, positions
/// resampled by interpolation or held between updates) does not pass for motion; what is left
/// above the floor is weighted by (2 pi f)^2 for the velocities.
/// Throws DataError naming the source for non-uniform sampling, fewer than 16 samples,
/// non-finite positions, positions that do not move above their noise; std::invalid_argument
/// for energy_fraction outside (0, 1).
ExcitationBands estimate_bands(const Trajectory& trajectory, double energy_fraction = 0.99);

/// estimate_bands(trajectory, energy_fraction).bandwidth_hz.
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

/// The decimation keeps kKeptBandMultiple x the bandwidth, and more only where the rows need it
/// (kRowsPerParameter). Why 2: the bandwidth already holds the torques' own band (estimate_bands),
/// and products of two motion terms reach twice the motion's band (kTorqueBandFactor); above
/// that, W holds no motion, so the rows there add no information on the parameters, only the
/// torques' noise (under a controller its coloured answer to the encoder noise, which the
/// standard deviations take for white) and the accelerations' noise, whose power grows as the
/// fifth power of the kept band (errors in the variables). Measured (issue 31): the kept band at
/// 4x against 2x, the rows bound as it is, on the TX-40 test record of
/// closed_loop_preparation_test left the truth 0.050 against 0.034 of relative error, and on the
/// real Panda run the consistent fit 1.097x against 0.992x the unconstrained one's error; on the
/// 30 s PUMA 560 and TX-40 closed-loop records the rows bound decides either way (n_d = 140).
inline constexpr double kKeptBandMultiple = 2.0;
/// Rows of the decimated equations per unknown the plan keeps at least (RowBudget): with fewer,
/// the standard deviations rest on a residual of few degrees of freedom per parameter and the
/// well-determined parameters are few (issue 31: 73 rows per axis for 58 parameters).
inline constexpr double kRowsPerParameter = 20.0;

/// What the decimation must leave: `samples` per axis after filtering, `axes` equations per
/// sample, `unknowns` parameters. A budget with unknowns = 0 imposes nothing.
struct RowBudget {
  long long samples = 0;
  int axes = 0;
  int unknowns = 0;
};

/// Gautier's practice, as a rule: the position filter must not touch the dynamics, so its
/// cut-off is 10 x the bandwidth (at most 0.8 x Nyquist); the decimation keeps the identified
/// frequency range, so n_d is the largest factor whose decimation filter cut-off,
/// 0.8 (fs / 2) / n_d, is still at least kKeptBandMultiple x the bandwidth (n_d = 1 when none
/// is), that leaves at least kRowsPerParameter rows per unknown of `rows` (samples x axes /
/// n_d >= 20 unknowns) and that runs in stages of at most 10 (decimation_factor_below: 71
/// becomes 70 = 10 x 7). The explanation says which bound chose n_d.
/// Throws std::invalid_argument for a sample rate <= 0 or a bandwidth not in (0, fs / 2).
FilterPlan plan_filtering(double sample_rate_hz, double bandwidth_hz, const RowBudget& rows = {});

}  // namespace modelgen
