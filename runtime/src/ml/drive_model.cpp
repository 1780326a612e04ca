// The reference drive model (Swevers et al. 2002, eq. 5-12): rigid-body gear torques from the
// numeric reference's standard regressor, computed once per sample, and the analytic Jacobian of
// the motor torques with respect to the inertial and drive parameters.

#include "modelgen/ml/drive_model.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <stdexcept>
#include <utility>

namespace modelgen {
namespace {

// The tree with only its inertial parameters: the rigid-body part of the drive model, whose
// rotor inertia and friction are the motor-side JM, Rv, Rc instead of Ia, Fv, Fc.
RigidBodyTree rigid_body_part(const RigidBodyTree& tree) {
  RigidBodyTree rigid = tree;
  rigid.params.clear();
  rigid.coupled_motors.clear();
  for (const StandardParam& param : tree.params) {
    if (is_inertial(param.kind)) rigid.params.push_back(param);
  }
  return rigid;
}

}  // namespace

ReferenceDriveModel::ReferenceDriveModel(const RigidBodyTree& tree, const DriveChain& drive)
    : dof_(tree.dof), rigid_(rigid_body_part(tree)) {
  inertial_ = rigid_.num_params();
  for (const StandardParam& param : rigid_.tree().params) names_.push_back(param.name);
  std::vector<int> joint_number(dof_, 0);
  for (size_t b = 0; b < tree.bodies.size(); ++b) {
    if (tree.bodies[b].dof_index >= 0) joint_number[tree.bodies[b].dof_index] = int(b) + 1;
  }
  for (int i = 0; i < dof_; ++i) {
    const std::string j = std::to_string(joint_number[i]);
    for (const char* stem : {"JM", "Rv", "Rc", "Rz"}) names_.push_back(stem + j);
  }
  K_ = drive.motor_from_joint.size() == 0 ? Eigen::MatrixXd::Identity(dof_, dof_)
                                          : drive.motor_from_joint;
  if (K_.rows() != dof_ || K_.cols() != dof_) {
    throw std::invalid_argument("drive model: motor_from_joint is " + std::to_string(K_.rows()) +
                                " x " + std::to_string(K_.cols()) + ", expected " +
                                std::to_string(dof_) + " x " + std::to_string(dof_));
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(K_);
  if (!lu.isInvertible()) {
    throw std::invalid_argument("drive model: motor_from_joint is singular (rank " +
                                std::to_string(lu.rank()) + " of " + std::to_string(dof_) + ")");
  }
  K_inv_T_ = lu.inverse().transpose();
}

void ReferenceDriveModel::set_samples(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                                      const Eigen::MatrixXd& ddq) {
  const Eigen::Index n = q.rows();
  if (q.cols() != dof_ || dq.cols() != dof_ || ddq.cols() != dof_ || dq.rows() != n ||
      ddq.rows() != n) {
    throw std::invalid_argument("drive model: q, dq, ddq must be samples x " +
                                std::to_string(dof_) + " matrices of equal size");
  }
  samples_ = n;
  A_.assign(static_cast<size_t>(n * dof_ * inertial_), 0.0);
  // Swevers eq. 9: motor velocities and accelerations from the joint ones, dq_M = K dq.
  dq_M_ = K_ * dq.transpose();
  ddq_M_ = K_ * ddq.transpose();
  for (Eigen::Index s = 0; s < n; ++s) {
    const Eigen::MatrixXd W = rigid_.standard_regressor(q.row(s).transpose(), dq.row(s).transpose(),
                                                        ddq.row(s).transpose());
    // Eq. 10: tau'_G = V^T tau_G = K^-T W_std p.
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        &A_[static_cast<size_t>(s * dof_ * inertial_)], dof_, inertial_) = K_inv_T_ * W;
  }
}

void ReferenceDriveModel::torque_jacobian(Eigen::Index sample, const double* theta, double* tau_M,
                                          double* J) const {
  const int P = num_params();
  const double* A = &A_[static_cast<size_t>(sample * dof_ * inertial_)];
  for (int i = 0; i < dof_; ++i) {
    double* row = J + static_cast<size_t>(i) * P;
    std::fill(row, row + P, 0.0);
    double tau_pg = 0;
    for (int k = 0; k < inertial_; ++k) tau_pg += A[i * inertial_ + k] * theta[k];
    const double* drive = theta + inertial_ + kDriveParamsPerMotor * i;
    const double dq_M = dq_M_(i, sample), ddq_M = ddq_M_(i, sample), Rz = drive[3];
    const double power = tau_pg * dq_M;
    const double s = power > 0 ? 1.0 : (power < 0 ? -1.0 : 0.0);
    const double sign_dq = dq_M > 0 ? 1.0 : (dq_M < 0 ? -1.0 : 0.0);
    // Eq. 8 inverted: tau_T = tau'_G g(Rz), g = (1 + s) / (2 Rz) + (1 - s) Rz / 2; s is
    // piecewise constant, so d g / d Rz = -(1 + s) / (2 Rz^2) + (1 - s) / 2 away from switches.
    const double g = (1 + s) / 2 / Rz + (1 - s) / 2 * Rz;
    tau_M[i] = tau_pg * g + drive[0] * ddq_M + drive[1] * dq_M + drive[2] * sign_dq;
    for (int k = 0; k < inertial_; ++k) row[k] = g * A[i * inertial_ + k];
    double* d = row + inertial_ + kDriveParamsPerMotor * i;
    d[0] = ddq_M;  // eq. 6
    d[1] = dq_M;   // eq. 5
    d[2] = sign_dq;
    d[3] = tau_pg * (-(1 + s) / 2 / (Rz * Rz) + (1 - s) / 2);
  }
}

}  // namespace modelgen
