// modelid's side of torque prediction: progress on stderr, CSV output.

#include "runtime/cli/reports/prediction_output.hpp"

#include <algorithm>
#include <cmath>

#include "runtime/cli/common/progress.hpp"
#include "runtime/cli/common/text_format.hpp"

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
