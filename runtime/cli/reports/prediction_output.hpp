// Torque prediction as modelid shows it: the library's predict_decimated with a progress line,
// and the prediction as CSV.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/predict.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen::internal {

/// predict_decimated (modelgen/estimation/predict.hpp) with "modelid: predicting torques N%"
/// on stderr (runtime/cli/progress.hpp).
TorquePrediction predict_with_progress(const IdentificationModel& model,
                                       std::vector<Trajectory>& data, const Eigen::VectorXd& beta,
                                       const std::vector<int>& decimation);

/// Throws InputError naming `params` (the parameter file) and the quantity when a number
/// predict prints or writes is not finite: a predicted torque or error (with its column, data
/// file and time), an rms value or error % of an axis, a relative error norm (NaN where the
/// measured torques are all zero is what it means, not an overflow). `cause` completes the
/// message (largest_parameter). Only predicted torques are judged without `measured`.
void check_prediction_finite(const std::string& params, const std::vector<Trajectory>& data,
                             const TorquePrediction& prediction, bool measured,
                             const std::string& cause);

/// CSV of the prediction, one row per sample, experiments one after the other: columns
/// experiment (1-based, in the order of `data`), t, then q1..qn when `with_positions`,
/// tau1..taun (measured), tau_pred1..tau_predn, error1..errorn (measured - predicted); only
/// tau_pred1..tau_predn without `with_measured` (data without torque columns).
/// Numbers in shortest round-trip form.
std::string prediction_csv(const std::vector<Trajectory>& data, const TorquePrediction& prediction,
                           bool with_positions, bool with_measured = true);

}  // namespace modelgen::internal
