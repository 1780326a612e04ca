// Does a non-periodic preparation suit its data? The encoder noise read from the positions'
// spectrum far above the motion, the acceleration noise it leaves in the regressor (errors in
// the variables), the rows left per parameter and the band the decimation keeps: each check
// that fails gives one warning naming the likely cause and the option to change (issue 31).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"

namespace modelgen {

/// Per axis, the standard deviation of white noise on the positions `x.q` (rad; m for a
/// prismatic axis), read from their spectrum between fs / 4 and fs / 2, where no motion of a
/// robot lies: least-squares line removed, Hann window, the median line power over that range
/// divided by ln 2 (the median of exponentially distributed powers) and by the window's energy.
/// Quantisation of step r reads below r / sqrt(12) (its error is not white on a slow motion:
/// 0.65 and 0.81 times on two axes of sines). Uniform sampling assumed (as the callers
/// have); returns zeros for fewer than 64 samples.
Eigen::VectorXd position_noise_std(const Trajectory& x);

/// The standard deviation of the acceleration noise that white position noise of `q_std` leaves
/// after the position filter (4th-order Butterworth at `cutoff_hz`, zero phase), second
/// differences and a band kept up to `kept_hz` (the decimation's filter, Chebyshev I order 8
/// there, zero phase; none from 0.45 fs up), for
/// samples at `sample_rate_hz`: the noise's one-sided density 2 q_std^2 / fs times the squared
/// gains, integrated. Throws std::invalid_argument as butterworth_lowpass does.
double acceleration_noise_std(double q_std, double cutoff_hz, double kept_hz,
                              double sample_rate_hz);

/// What check_preparation looks at: the plan a non-periodic preparation ran with.
struct PreparationFacts {
  std::string source;  ///< the file, for the messages
  double sample_rate_hz = 0;
  double bandwidth_hz = 0;                              ///< the excitation's (estimated or given)
  double cutoff_hz = 0;                                 ///< the position filter's
  int decimation = 1;                                   ///< n_d
  bool cutoff_given = false, decimation_given = false;  ///< by the user (--cutoff, --decimate)
  int planned_decimation = 1;                           ///< what plan_filtering would choose
  double planned_cutoff_hz = 0;                         ///< what plan_filtering would choose
  long long samples = 0;                                ///< after the filter's edges
  int unknowns = 0;             ///< base parameters (0: unknown, no row check)
  Eigen::VectorXd q_noise_std;  ///< position_noise_std of the raw positions
  Eigen::MatrixXd ddq;          ///< the prepared accelerations (samples x axes)
  Eigen::MatrixXd tau;          ///< the measured torques on the same samples
};

/// Above this ratio of the acceleration noise's variance in the kept band to the accelerations'
/// own variance, the inertia terms are called attenuated (least squares with a noisy regressor
/// shrinks a coefficient by 1 / (1 + ratio): 1 %).
inline constexpr double kAttenuationRatio = 0.01;

/// The warnings ("SOURCE: warning: ...", one per failed check) for a preparation: errors in
/// the variables (the accelerations' noise in the band the decimation keeps, min(cutoff,
/// decimation cut-off), against their motion, above kAttenuationRatio on some axis); fewer
/// than kRowsPerParameter rows per unknown with a decimation given; a decimation that keeps a band
/// above the position filter's cut-off (the torques keep there what the regressor lost) or over 10
/// times the excitation's while more than 10 % of the torques' power in it lies above twice the
/// excitation band (closed-loop torques there are the controller's answer to encoder noise,
/// coloured, and the least-squares standard deviations assume white residuals). Empty when
/// every check passes.
std::vector<std::string> check_preparation(const PreparationFacts& facts);

}  // namespace modelgen
