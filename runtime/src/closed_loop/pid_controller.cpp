// The discrete PID of issue 13, sample by sample.

#include "modelgen/closed_loop/pid_controller.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace modelgen {

void PidGains::check() const {
  if (!(sample_time > 0) || !std::isfinite(sample_time)) {
    throw std::invalid_argument("PID: the sample time must be a positive number of seconds, got " +
                                std::to_string(sample_time));
  }
  const auto n = kp.size();
  if (n == 0 || ki.size() != n || kd.size() != n) {
    throw std::invalid_argument("PID: kp, ki and kd need one gain per joint, got " +
                                std::to_string(kp.size()) + ", " + std::to_string(ki.size()) +
                                " and " + std::to_string(kd.size()));
  }
  const struct {
    const char* name;
    const Eigen::VectorXd& gains;
  } lists[] = {{"kp", kp}, {"ki", ki}, {"kd", kd}};
  for (const auto& list : lists) {
    for (Eigen::Index j = 0; j < n; ++j) {
      const double g = list.gains[j];
      if (!std::isfinite(g) || g < 0) {
        throw std::invalid_argument("PID: " + std::string(list.name) + " of joint " +
                                    std::to_string(j + 1) + " must be a finite gain >= 0, got " +
                                    std::to_string(g));
      }
    }
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    if (kp[j] == 0) {
      throw std::invalid_argument("PID: kp of joint " + std::to_string(j + 1) +
                                  " is 0: without a proportional gain the loop does not hold "
                                  "the joint");
    }
  }
}

PidController::PidController(PidGains gains) : gains_(std::move(gains)) {
  gains_.check();
  reset();
}

void PidController::reset() {
  error_sum_ = Eigen::VectorXd::Zero(dof());
  previous_error_ = Eigen::VectorXd::Zero(dof());
  started_ = false;
}

Eigen::VectorXd PidController::command(const Eigen::VectorXd& qr, const Eigen::VectorXd& q) {
  const Eigen::VectorXd e = qr - q;
  if (!started_) previous_error_ = e;
  started_ = true;
  error_sum_ += e;
  const double ts = gains_.sample_time;
  Eigen::VectorXd tau = gains_.kp.cwiseProduct(e) + ts * gains_.ki.cwiseProduct(error_sum_) +
                        gains_.kd.cwiseProduct(e - previous_error_) / ts;
  previous_error_ = e;
  return tau;
}

}  // namespace modelgen
