// Joint torques predicted from base parameters for measured trajectories, and how far they are
// from the measured ones: rms per axis (Swevers 2002, Table 3) and the relative error norm
// ||tau - tau_pred|| / ||tau|| (Gautier & Briot, Tables III-IV).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen::internal {

struct TorquePrediction {
  /// Per experiment, samples x dof like its Trajectory: predicted torques (N m, N) and
  /// measured minus predicted.
  std::vector<Eigen::MatrixXd> tau_pred, error;
  /// Per axis over all experiments: rms of the measured torque and of the error (dof entries).
  Eigen::VectorXd rms_torque, rms_error;
  /// ||tau - tau_pred|| / ||tau|| over all samples and axes, and per experiment; NaN when the
  /// measured torques are all zero.
  double rel_error_norm = 0;
  std::vector<double> rel_error_norm_per_experiment;
  long long samples = 0;
};

/// tau_pred = model.inverse_dynamics(q, dq, ddq, beta) for every sample of every experiment
/// (each with dq, ddq set and dof() columns); beta has num_base_params() entries.
/// Throws std::invalid_argument on mismatched sizes.
TorquePrediction predict_torques(const IdentificationModel& model,
                                 const std::vector<Trajectory>& data, const Eigen::VectorXd& beta);

/// The comparison identification makes after the parallel decimation (Gautier & Briot eq.
/// 13-14): torques predicted at the full rate, then for each experiment with a factor
/// decimation[e] > 1 the measured and the predicted torques pass the same decimation filter
/// (decimate(W) beta = decimate(W beta)); data[e] is replaced by its decimated trajectory
/// (decimate_trajectory), so rows of the prediction and of data still match. Factors of 1, or
/// missing, leave an experiment as it is.
TorquePrediction predict_decimated(const IdentificationModel& model, std::vector<Trajectory>& data,
                                   const Eigen::VectorXd& beta, const std::vector<int>& decimation);

/// CSV of the prediction, one row per sample, experiments one after the other: columns
/// experiment (1-based, in the order of `data`), t, then q1..qn when `with_positions`,
/// tau1..taun (measured), tau_pred1..tau_predn, error1..errorn (measured - predicted); only
/// tau_pred1..tau_predn without `with_measured` (data without torque columns).
/// Numbers in shortest round-trip form.
std::string prediction_csv(const std::vector<Trajectory>& data, const TorquePrediction& prediction,
                           bool with_positions, bool with_measured = true);

}  // namespace modelgen::internal
