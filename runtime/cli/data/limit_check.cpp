// The joint-limit check of fit and predict.

#include "runtime/cli/data/limit_check.hpp"

#include <cmath>

#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

namespace {

// Measured data (and filtered derivatives) may overshoot a limit slightly.
constexpr double kTolerance = 0.01;

// The likely causes of values `times` the size of the limit.
std::string likely_cause(double times, Side side) {
  std::string cause;
  if (side == Side::kJoint && times > 3) cause = "motor-side data read as joint data (--motor-side)?";
  if (times > 20 && times < 120) cause += std::string(cause.empty() ? "" : " ") + "degrees instead of radians?";
  if (cause.empty()) cause = "a joint offset, or a wrong zero of the encoders?";
  return cause;
}

}  // namespace

int warn_beyond_limits(std::ostream& err, const std::string& command, const ModelSource& source,
                       const Experiments& experiments, Side side) {
  int warnings = 0;
  for (const Trajectory& x : experiments.data) {
    for (std::size_t j = 0; j < source.limits.size() && static_cast<Eigen::Index>(j) < x.q.cols();
         ++j) {
      const JointLimits& limit = source.limits[j];
      const std::string joint =
          "joint " + std::to_string(j + 1) + " ('" + source.joint_names[j] + "')";
      const double low = x.q.col(j).minCoeff(), high = x.q.col(j).maxCoeff();
      if (limit.q_lower && limit.q_upper) {
        const double span = *limit.q_upper - *limit.q_lower;
        const double out = high > *limit.q_upper + kTolerance * span ? high
                           : low < *limit.q_lower - kTolerance * span ? low
                                                                       : NAN;
        if (!std::isnan(out)) {
          const double reach = std::max(std::abs(*limit.q_lower), std::abs(*limit.q_upper));
          err << "modelid " << command << ": warning: " << x.source << ": " << joint
              << " reaches q = " << fixed(out, 0, 4) << ", outside its limits ["
              << fixed(*limit.q_lower, 0, 4) << ", " << fixed(*limit.q_upper, 0, 4)
              << "] in the description: " << likely_cause(std::abs(out) / reach, side) << "\n";
          ++warnings;
        }
      }
      if (limit.dq && x.has_velocity) {
        const double speed = x.dq.col(j).cwiseAbs().maxCoeff();
        if (speed > (1 + kTolerance) * *limit.dq) {
          err << "modelid " << command << ": warning: " << x.source << ": " << joint
              << " reaches |dq| = " << fixed(speed, 0, 4) << ", above its velocity limit "
              << fixed(*limit.dq, 0, 4) << " in the description: "
              << likely_cause(speed / *limit.dq, side) << "\n";
          ++warnings;
        }
      }
    }
  }
  return warnings;
}

}  // namespace modelgen::internal
