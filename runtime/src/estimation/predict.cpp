// Torque prediction sample by sample through the model's inverse dynamics on base parameters
// (tau = W(q, dq, ddq) beta, Gautier & Briot eq. 4-6) and the error statistics of the
// validation tables (Swevers 2002 Table 3, Gautier & Briot Tables III-IV).

#include "modelgen/estimation/predict.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "modelgen/signal/decimation.hpp"

namespace modelgen {

namespace {

// ||a|| / ||b||, NaN when b is zero (no measured torque to compare with).
double ratio(double error_square_sum, double torque_square_sum) {
  return torque_square_sum > 0 ? std::sqrt(error_square_sum / torque_square_sum)
                               : std::numeric_limits<double>::quiet_NaN();
}

// The statistics of predicted against measured torques, experiment by experiment.
TorquePrediction compare(const std::vector<Trajectory>& data,
                         std::vector<Eigen::MatrixXd> predicted) {
  const Eigen::Index n = data.empty() ? 0 : data.front().q.cols();
  TorquePrediction out;
  Eigen::VectorXd error_squares = Eigen::VectorXd::Zero(n),
                  torque_squares = Eigen::VectorXd::Zero(n);
  for (std::size_t e = 0; e < data.size(); ++e) {
    const Trajectory& x = data[e];
    Eigen::MatrixXd error = x.tau - predicted[e];
    const Eigen::VectorXd e2 = error.colwise().squaredNorm().transpose();
    const Eigen::VectorXd t2 = x.tau.colwise().squaredNorm().transpose();
    out.rel_error_norm_per_experiment.push_back(ratio(e2.sum(), t2.sum()));
    error_squares += e2;
    torque_squares += t2;
    out.samples += x.t.size();
    out.tau_pred.push_back(std::move(predicted[e]));
    out.error.push_back(std::move(error));
  }
  out.rel_error_norm = ratio(error_squares.sum(), torque_squares.sum());
  const double samples = static_cast<double>(std::max(out.samples, 1LL));
  out.rms_error = (error_squares / samples).cwiseSqrt();
  out.rms_torque = (torque_squares / samples).cwiseSqrt();
  return out;
}

}  // namespace

TorquePrediction predict_torques(const IdentificationModel& model,
                                 const std::vector<Trajectory>& data, const Eigen::VectorXd& beta,
                                 const ProgressCallback& progress) {
  const int n = model.dof();
  if (beta.size() != model.num_base_params()) {
    throw std::invalid_argument("predict_torques: " + std::to_string(beta.size()) +
                                " base parameters given, the model has " +
                                std::to_string(model.num_base_params()));
  }
  long long total = 0;
  for (const Trajectory& x : data) {
    const Eigen::Index m = x.t.size();
    for (const Eigen::MatrixXd* a : {&x.q, &x.dq, &x.ddq, &x.tau}) {
      if (a->rows() != m || a->cols() != n) {
        throw std::invalid_argument(x.source + ": q, dq, ddq and tau need " + std::to_string(m) +
                                    " rows and " + std::to_string(n) + " columns");
      }
    }
    total += m;
  }
  const double per_sample = 1.0 / static_cast<double>(std::max(total, 1LL));
  const auto report = [&](long long done) {
    if (progress) progress(static_cast<double>(done) * per_sample);
  };
  long long done = 0;
  std::vector<double> tau(n);
  std::vector<Eigen::MatrixXd> predicted;
  for (const Trajectory& x : data) {
    Eigen::MatrixXd tau_pred(x.t.size(), n);
    for (Eigen::Index s = 0; s < x.t.size(); ++s, ++done) {
      if (done % 1024 == 0) report(done);
      const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
      model.inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau.data());
      for (int j = 0; j < n; ++j) tau_pred(s, j) = tau[j];
    }
    predicted.push_back(std::move(tau_pred));
  }
  report(done);
  return compare(data, std::move(predicted));
}

TorquePrediction predict_decimated(const IdentificationModel& model, std::vector<Trajectory>& data,
                                   const Eigen::VectorXd& beta, const std::vector<int>& decimation,
                                   const ProgressCallback& progress) {
  TorquePrediction full = predict_torques(model, data, beta, progress);
  for (std::size_t e = 0; e < data.size() && e < decimation.size(); ++e) {
    if (decimation[e] == 1) continue;
    // Eq. 14: decimate(W) beta = decimate(W beta), the same filter on both sides, the same
    // rows kept as identify() keeps.
    full.tau_pred[e] = decimate_interior(full.tau_pred[e], decimation[e]);
    decimate_trajectory(data[e], decimation[e]);
  }
  return compare(data, std::move(full.tau_pred));
}

}  // namespace modelgen
