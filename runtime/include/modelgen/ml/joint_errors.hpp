// The ML route's torque errors on the joint side: Swevers eq. 18 compares motor torques; a
// check against the joint-side noise of the averaged periods needs them where the record's
// torques are (issue 31).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace modelgen {

/// Joint-side errors, one N x dof matrix per experiment, and which joints they judge.
struct MlJointErrors {
  std::vector<Eigen::MatrixXd> errors;
  std::vector<bool> judged;
};

/// `motor_errors`: measured minus modelled motor torque (MlProblem::torque_errors: the
/// experiments' samples stacked in order, `samples` per experiment, 0 on motors not in `axes`),
/// K the drive chain's motor_from_joint. tau_joint = K^T tau_M (power balance), so a sample's
/// joint error is K^T e_M. A joint j that a motor i outside `axes` drives (K_ij != 0) gets an
/// incomplete error and is not judged. Throws std::invalid_argument when sizes differ or an
/// axis does not exist.
MlJointErrors ml_joint_errors(const Eigen::MatrixXd& motor_errors, const Eigen::MatrixXd& K,
                              const std::vector<int>& axes,
                              const std::vector<Eigen::Index>& samples);

}  // namespace modelgen
