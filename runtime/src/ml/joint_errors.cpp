// Motor torque errors brought to the joints, and the joints an omitted motor leaves incomplete.

#include "modelgen/ml/joint_errors.hpp"

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace modelgen {

MlJointErrors ml_joint_errors(const Eigen::MatrixXd& motor_errors, const Eigen::MatrixXd& K,
                              const std::vector<int>& axes,
                              const std::vector<Eigen::Index>& samples) {
  const Eigen::Index n = K.rows();
  Eigen::Index total = 0;
  for (const Eigen::Index s : samples) total += s;
  if (K.cols() != n || motor_errors.cols() != n || motor_errors.rows() != total) {
    throw std::invalid_argument("ml_joint_errors: " + std::to_string(motor_errors.rows()) + " x " +
                                std::to_string(motor_errors.cols()) + " errors for " +
                                std::to_string(total) + " samples of " + std::to_string(n) +
                                " axes");
  }
  std::vector<bool> fitted(static_cast<std::size_t>(n), false);
  for (const int i : axes) {
    if (i < 0 || i >= n)
      throw std::invalid_argument("ml_joint_errors: no axis " + std::to_string(i));
    fitted[static_cast<std::size_t>(i)] = true;
  }
  MlJointErrors out;
  out.judged.assign(static_cast<std::size_t>(n), true);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (fitted[static_cast<std::size_t>(i)]) continue;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (K(i, j) != 0) out.judged[static_cast<std::size_t>(j)] = false;
    }
  }
  // Rows are samples: (K^T e)^T = e^T K.
  const Eigen::MatrixXd joint = motor_errors * K;
  Eigen::Index at = 0;
  for (const Eigen::Index s : samples) {
    out.errors.push_back(joint.middleRows(at, s));
    at += s;
  }
  return out;
}

}  // namespace modelgen
