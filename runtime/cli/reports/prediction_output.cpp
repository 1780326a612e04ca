// modelid's side of torque prediction: progress on stderr, the check that every number
// shown or written is finite, CSV output.

#include "runtime/cli/reports/prediction_output.hpp"

#include <algorithm>
#include <cmath>

#include "modelgen/model/error.hpp"
#include "modelgen/model/number_text.hpp"
#include "runtime/cli/common/progress.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/reports/finite_output.hpp"

namespace modelgen::internal {

TorquePrediction predict_with_progress(const IdentificationModel& model,
                                       std::vector<Trajectory>& data, const Eigen::VectorXd& beta,
                                       const std::vector<int>& decimation) {
  long long total = 0;
  for (const Trajectory& x : data) total += x.t.size();
  const long long scale = std::max(total, 1LL);
  Progress progress("predicting torques", total);
  return predict_decimated(model, data, beta, decimation, [&](double fraction) {
    progress.update(std::llround(fraction * static_cast<double>(scale)));
    // The line goes once every sample is predicted, before the decimation.
    if (fraction >= 1.0) progress.finish();
  });
}

void check_prediction_finite(const std::string& params, const std::vector<Trajectory>& data,
                             const TorquePrediction& prediction, bool measured,
                             const std::string& cause) {
  const auto refuse = [&](const std::string& what) {
    throw InputError({params}, what + ", beyond the range of a double" + cause +
                                   "; predict prints and writes finite numbers only, and wrote "
                                   "nothing");
  };
  for (std::size_t e = 0; e < data.size(); ++e) {
    const std::string of = " of " + data[e].source;
    const std::string pred = first_non_finite(prediction.tau_pred[e], data[e].t, "tau_pred");
    if (!pred.empty()) refuse("the predicted torque " + pred + of);
    if (!measured) continue;
    const std::string error = first_non_finite(prediction.error[e], data[e].t, "error");
    if (!error.empty()) refuse("the torque error " + error + of);
  }
  if (!measured) return;
  for (Eigen::Index j = 0; j < prediction.rms_torque.size(); ++j) {
    const std::string axis = " of axis " + std::to_string(j + 1) + " is ";
    const double torque = prediction.rms_torque[j], error = prediction.rms_error[j];
    if (!std::isfinite(torque)) refuse("the rms torque" + axis + shortest_text(torque));
    if (!std::isfinite(error)) refuse("the rms error" + axis + shortest_text(error));
    if (torque > 0 && !std::isfinite(100.0 * error / torque)) {
      refuse("the error %" + axis + shortest_text(100.0 * error / torque));
    }
  }
  // NaN is the norm's value where there is no measured torque to divide by.
  const auto judge = [&](double norm, bool torque, const std::string& what) {
    if (!std::isfinite(norm) && (torque || !std::isnan(norm))) {
      refuse("the relative error norm" + what + " is " + shortest_text(norm));
    }
  };
  bool any_torque = false;
  for (std::size_t e = 0; e < data.size(); ++e) {
    const bool torque = data[e].tau.cwiseAbs().maxCoeff() > 0;
    any_torque |= torque;
    judge(prediction.rel_error_norm_per_experiment[e], torque, " of " + data[e].source);
  }
  judge(prediction.rel_error_norm, any_torque, "");
}

std::string prediction_csv(const std::vector<Trajectory>& data, const TorquePrediction& prediction,
                           bool with_positions, bool with_measured) {
  const Eigen::Index n = data.empty() ? 0 : data.front().q.cols();
  std::string text = "experiment,t";
  std::vector<const char*> prefixes = {"tau", "tau_pred", "error"};
  if (!with_measured) prefixes = {"tau_pred"};
  if (with_positions) prefixes.insert(prefixes.begin(), "q");
  for (const char* prefix : prefixes) {
    for (Eigen::Index j = 0; j < n; ++j) text += "," + std::string(prefix) + std::to_string(j + 1);
  }
  text += "\n";
  for (std::size_t e = 0; e < data.size(); ++e) {
    const Trajectory& x = data[e];
    std::vector<const Eigen::MatrixXd*> blocks = {&x.tau, &prediction.tau_pred[e],
                                                  &prediction.error[e]};
    if (!with_measured) blocks = {&prediction.tau_pred[e]};
    if (with_positions) blocks.insert(blocks.begin(), &x.q);
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      text += std::to_string(e + 1) + "," + shortest(x.t[s]);
      for (const Eigen::MatrixXd* block : blocks) {
        for (Eigen::Index j = 0; j < n; ++j) text += "," + shortest((*block)(s, j));
      }
      text += "\n";
    }
  }
  return text;
}

}  // namespace modelgen::internal
