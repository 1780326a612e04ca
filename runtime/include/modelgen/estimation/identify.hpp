// From trajectories to base-parameter estimates: the stacked IDIM (torques, one equation per
// joint and sample) or PIM (power, one equation per sample) with OLS or WLS (Gautier & Briot
// eq. 14-20), and the torque prediction errors per axis.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/essential.hpp"
#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/least_squares.hpp"
#include "modelgen/estimation/progress.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen {

enum class Method {
  kOls,     ///< IDIM, ordinary least squares
  kWls,     ///< IDIM, one weight per joint and experiment (eq. 20)
  kPimWls,  ///< PIM, one weight per experiment (power equations, eq. 21)
};

/// "ols", "wls", "pim-wls"; throws EstimationError for anything else.
Method parse_method(const std::string& text);

struct Identification {
  LeastSquaresResult fit;          ///< base parameters in model.base_param_names() order
  std::vector<std::string> names;  ///< model.base_param_names()
  /// Per joint, over all experiments: rms of measured minus predicted torque, and rms of the
  /// measured torque (Swevers Table 3 style).
  Eigen::VectorXd rms_error, rms_torque;
  /// ||tau - W beta|| / ||tau|| over all torque equations (Gautier & Briot Tables III-IV).
  double torque_rel_error_norm = 0;
  Eigen::Index samples = 0;  ///< samples used, after decimation
  /// Samples (decimated rows for a decimated experiment) left out by IdentifyOptions::min_speed.
  Eigen::Index slow_samples = 0;
  /// Essential parameters (IdentifyOptions::essential_r_sigma set): indices into `names`.
  EssentialParameters essential;
};

/// What identify() does besides the plain fit.
struct IdentifyOptions {
  /// Parallel decimation factor per experiment (Gautier & Briot eq. 13-14; empty: none). For an
  /// experiment with a factor n_d > 1, its W (samples x dof rows) and torque vector are built
  /// whole, every column of each joint's rows and the torques low-passed with the same
  /// zero-phase filter and one sample in n_d kept (decimate() of
  /// modelgen/signal/decimation.hpp); the PIM's power rows and powers likewise. Memory then
  /// grows with that experiment's samples times the base parameters for the duration of its
  /// reduction.
  std::vector<int> decimation;
  /// Per experiment (empty: none): -1, or H >= 0 when the experiment is one averaged period whose
  /// torques keep only the harmonics 0..H (the periodic route of modelgen/signal/prepare.hpp).
  std::vector<int> torque_harmonics;
  /// Per joint, a speed (rad/s, m/s for prismatic joints; >= 0) below which a sample is left
  /// out: where a joint reverses, sign(dq) of the Coulomb model flips at a dq the preparation
  /// only estimates, and the measured torque goes through the friction's true, smooth
  /// transition; empty keeps every sample. A sample is left out when any joint is slower than
  /// its speed. For a decimated experiment the test is made on the decimated rows, dq decimated
  /// with the same filter as W and Y (after eq. 13-14: leaving out samples before the filter
  /// would break the filter, not the equations).
  std::vector<double> min_speed;
  /// Per experiment (empty: 0 for all), with min_speed, for a decimated experiment: before the
  /// decimation each joint's equations within this many samples of a sample where it (or a
  /// motor coupled to it) is slower than its speed are zeroed on both sides (reversal_mask,
  /// modelgen/signal/reversal_mask.hpp): the position filter's impulse length
  /// (PreparedExperiment::reversal_guard).
  std::vector<Eigen::Index> reversal_guard;
  ProgressCallback progress;
  /// When set, also the essential parameters for this r_sigma (Identification::essential).
  std::optional<double> essential_r_sigma;
};

/// Identifies the base parameters of `model` from `data` (each trajectory with dq and ddq set,
/// dof columns). The regressor rows go straight into a LeastSquaresAccumulator (one group per
/// joint and experiment for the IDIM, per experiment for the PIM) in two threads; W is never
/// stored, so memory does not grow with the number of samples beyond `data` itself.
/// `model`'s functions are called from two threads at once (both shipped kinds are stateless).
/// `progress`, when given, is called from the calling thread only, at most ~100 times, last
/// with 1; an exception it throws cancels the identification and propagates.
/// Throws EstimationError with the reason: a trajectory with no samples, wrong sizes or a
/// non-finite value (naming the source, sample and column), rank deficiency (naming the
/// parameters), too few samples.
Identification identify(const IdentificationModel& model, const std::vector<Trajectory>& data,
                        Method method, const ProgressCallback& progress = nullptr);

/// identify() with options (decimation, minimum speed, essential parameters). Also throws
/// EstimationError for a decimation list that does not have one factor (>= 1) per experiment,
/// a factor that leaves an experiment too few samples, a min_speed list that does not have one
/// value (>= 0) per joint, or one that leaves out every sample of an experiment (the message
/// gives the experiment's largest speed per joint).
Identification identify(const IdentificationModel& model, const std::vector<Trajectory>& data,
                        Method method, const IdentifyOptions& options);

}  // namespace modelgen
