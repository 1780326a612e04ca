// One measured experiment made ready for identification: to the joint side through the drive
// chain, then either the periodic route of Swevers et al. 2002 (average the periods, estimate
// the noise, re-estimate the Fourier series, analytic derivatives) or the non-periodic route of
// Gautier & Briot (zero-phase position filter, central differences, and a decimation factor
// for the parallel decimation of Y and W that identify() applies).
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/joint_side.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/model/drive_chain.hpp"
#include "modelgen/signal/periodic_noise.hpp"

namespace modelgen {

/// How to prepare the experiments; every unset value is chosen from the data.
struct PreparationOptions {
  Side side = Side::kJoint;  ///< where positions (and torques) were measured
  /// Periodic excitation (Swevers): average the periods and re-estimate the Fourier series.
  bool periodic = false;
  std::optional<double> period;  ///< s; detected from the positions when unset
  std::optional<int> harmonics;  ///< Fourier harmonics kept; select_harmonics() when unset
  /// Periodic route: whole periods at the start of the record left out of the average. A
  /// record under a controller starts with a transient (the integrator settling, the start
  /// from rest) that is not periodic: averaged in, it counts as noise, the noise estimates
  /// (and every weight built on them) grow, and the averaged period is biased.
  int skip_periods = 0;
  /// Non-periodic data without dq/ddq columns: no position filter and no decimation, only
  /// central differences (for clean, e.g. simulated, data).
  bool raw = false;
  std::optional<double> bandwidth_hz;  ///< excitation bandwidth; estimated when unset
  std::optional<double> cutoff_hz;     ///< position filter cut-off; from plan_filtering
  std::optional<int> decimation;       ///< n_d; from plan_filtering (1 for data with dq/ddq)
  /// The unknowns the prepared rows will estimate (base parameters): plan_filtering leaves at
  /// least kRowsPerParameter rows per unknown; 0 sets no such bound.
  int unknowns = 0;
  /// For prediction: one row per input sample, at the file's own time stamps, with its
  /// measured torques. The motion is made as the route says (zero-phase filtered positions
  /// and their central differences, the Fourier series of the averaged period, or dq and ddq
  /// as given) and linearly interpolated back to the time stamps when the route resampled,
  /// averaged or dropped samples; the filter's edges are kept; the decimation factor is 1.
  bool every_sample = false;
  /// The torques are commands held over each sample, tau_k over [t_k, t_k+1) (a digital
  /// controller's zero-order hold): the torque acting at t_k is then best (tau_k-1 + tau_k) / 2,
  /// the held signal delayed by half a sample, and each tau_k is replaced by it before anything
  /// else (the first sample extrapolated linearly). No filter undoes a delay, zero phase or not:
  /// on the simulated TX-40 of closed_loop_preparation_test it takes the relative error norm
  /// from 0.031 to 0.025.
  bool torque_hold = false;
};

struct PreparedExperiment {
  Trajectory data;     ///< joint side, with dq and ddq
  int decimation = 1;  ///< parallel decimation factor for identify() (eq. 13-14)
  /// Non-periodic route with a position filter: the excitation bandwidth used (given or
  /// estimated), Hz; 0 otherwise.
  double bandwidth_hz = 0;
  /// Non-periodic route with a position filter: its impulse length in samples
  /// (reversal_guard_samples), how far the prepared velocity's error at a reversal reaches
  /// (IdentifyOptions::reversal_guard); 0 otherwise.
  Eigen::Index reversal_guard = 0;
  /// With a position filter: per joint, the speed below which the prepared velocity's sign is
  /// unreliable (reversal_min_speed's choice, rad/s or m/s); empty otherwise.
  Eigen::VectorXd reversal_speed;
  /// Periodic route: noise variance of the averaged torque per axis ((N m)^2), else empty.
  Eigen::VectorXd tau_noise_variance;
  /// Periodic route: the noise of the prepared q, dq, ddq and tau (periodic_noise()), else empty.
  PeriodicNoise noise;
  std::string summary;  ///< what was done, in one or two lines, for the user
  std::string warning;  ///< e.g. the samples dropped after the last whole period; may be empty
};

/// Prepares one experiment as `options` say (see PreparationOptions). Data whose sampling is
/// not uniform (time stamps with jitter) are first resampled on a uniform grid by linear
/// interpolation (step: the mean step, or the median one when samples are missing, i.e. the
/// mean is more than 1% longer), and the summary says so.
/// Throws DataError naming the file for anything the steps reject (no period found, a
/// cut-off above Nyquist, too few samples, ...).
PreparedExperiment prepare_experiment(Trajectory raw, const DriveChain& drive,
                                      const PreparationOptions& options);

}  // namespace modelgen
