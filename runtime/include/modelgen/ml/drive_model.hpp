// The nonlinear drive model F of Swevers et al. 2002 (eq. 12): rigid-body gear torques, the
// coupling V (eq. 9-10), the transmission efficiency R_z (eq. 8) and the motor's rotor inertia
// and friction (eq. 5-7), giving motor torques (link side) from joint motion and parameters.
// DriveModel is the interface the maximum-likelihood fit works through; ReferenceDriveModel
// computes it from the numeric reference (any description, and, being a template in the
// parameters, the automatic-differentiation oracle); GeneratedDriveModel adapts generated code.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "modelgen/model/drive_chain.hpp"
#include "modelgen/model/generated_format.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen {

/// Drive parameters per motor, after the inertial parameters, in this order.
constexpr int kDriveParamsPerMotor = 4;  // JM, Rv, Rc, Rz

/// A drive model F: motor torques tau_M (dof values, N m, link side) of each bound sample from a
/// parameter vector theta (num_params() values, names in param_names() order: the inertial
/// standard parameters XXj..Mj of every link in standard order, then per motor j JMj (kg m^2),
/// Rvj (N m s/rad), Rcj (N m), Rzj (efficiency, > 0)).
/// Model, link side, K = motor_from_joint, for each motor i:
///   tau_G = W_std(q, dq, ddq) p (rigid body only), tau'_G = K^-T tau_G (eq. 10),
///   dq_M = K dq, ddq_M = K ddq (eq. 9), s = sign(tau'_G,i dq_M,i),
///   tau_T,i = tau'_G,i ((1 + s) / 2 / Rz_i + (1 - s) / 2 Rz_i) (eq. 8 inverted: a motor that
///   drives the link loses power, a link that drives the motor returns less),
///   tau_M,i = tau_T,i + JM_i ddq_M,i + Rv_i dq_M,i + Rc_i sign(dq_M,i) (eq. 5-7).
/// At the switch (tau'_G,i dq_M,i = 0) s = 0: when tau'_G,i = 0 nothing is transmitted, and when
/// the motor stands still (dq_M,i = 0) the efficiency factor is the mean of both branches.
/// Implementations must allow torque() and torque_jacobian() from several threads at once.
class DriveModel {
 public:
  virtual ~DriveModel() = default;

  virtual int dof() const = 0;
  virtual const std::vector<std::string>& param_names() const = 0;
  int num_params() const { return static_cast<int>(param_names().size()); }

  /// Binds the samples the other calls refer to by index: q, dq, ddq are samples x dof, joint
  /// side (rad, rad/s, rad/s^2). Throws std::invalid_argument on sizes that do not match.
  virtual void set_samples(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                           const Eigen::MatrixXd& ddq) = 0;
  virtual Eigen::Index num_samples() const = 0;

  /// tau_M of bound sample `sample` (dof values) for `theta` (num_params() values).
  virtual void torque(Eigen::Index sample, const double* theta, double* tau_M) const = 0;
  /// tau_M as torque() and its analytic Jacobian d tau_M / d theta into J: dof x num_params(),
  /// row-major. Entries that are zero for every sample (a generated model's structural zeros)
  /// may be left unwritten: zero J once before the first call, and let nothing else write it.
  virtual void torque_jacobian(Eigen::Index sample, const double* theta, double* tau_M,
                               double* J) const = 0;
};

/// Swevers eq. 5-8 for one motor: the motor torque from the gear torque on the motor side
/// `tau_pg` (tau'_G,i) and the motor velocity and acceleration. T is double or ceres::Jet.
template <class T>
T motor_torque_from_gear(const T& tau_pg, double dq_M, double ddq_M, const T& JM, const T& Rv,
                         const T& Rc, const T& Rz) {
  const T power = tau_pg * dq_M;
  const double s = power > 0.0 ? 1.0 : (power < 0.0 ? -1.0 : 0.0);
  const double sign_dq = dq_M > 0 ? 1.0 : (dq_M < 0 ? -1.0 : 0.0);
  const T tau_T = tau_pg * ((1 + s) / 2 / Rz + (1 - s) / 2 * Rz);
  return tau_T + JM * ddq_M + Rv * dq_M + Rc * sign_dq;
}

/// The drive model on the numeric reference: W_std from ReferenceDynamics::standard_regressor
/// (inertial columns only), computed once per bound sample since it does not depend on theta,
/// stored premultiplied by K^-T (samples x dof x inertial parameters doubles).
class ReferenceDriveModel final : public DriveModel {
 public:
  /// `drive.motor_from_joint` must be dof x dof and invertible. Throws std::invalid_argument for
  /// a malformed tree or drive chain.
  ReferenceDriveModel(const RigidBodyTree& tree, const DriveChain& drive);

  int dof() const override { return dof_; }
  const std::vector<std::string>& param_names() const override { return names_; }
  void set_samples(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                   const Eigen::MatrixXd& ddq) override;
  Eigen::Index num_samples() const override { return samples_; }
  void torque(Eigen::Index sample, const double* theta, double* tau_M) const override {
    evaluate(sample, theta, tau_M);
  }
  void torque_jacobian(Eigen::Index sample, const double* theta, double* tau_M,
                       double* J) const override;

  /// torque() for any scalar type: the automatic-differentiation oracle (T = ceres::Jet).
  template <class T>
  void evaluate(Eigen::Index sample, const T* theta, T* tau_M) const {
    const double* A = &A_[static_cast<size_t>(sample * dof_ * inertial_)];
    for (int i = 0; i < dof_; ++i) {
      T tau_pg = T(0.0);
      for (int k = 0; k < inertial_; ++k) tau_pg += A[i * inertial_ + k] * theta[k];
      const T* drive = theta + inertial_ + kDriveParamsPerMotor * i;
      tau_M[i] = motor_torque_from_gear(tau_pg, dq_M_(i, sample), ddq_M_(i, sample), drive[0],
                                        drive[1], drive[2], drive[3]);
    }
  }

 private:
  int dof_ = 0;
  int inertial_ = 0;  // inertial parameters at the front of theta
  std::vector<std::string> names_;
  ReferenceDynamics rigid_;  // the tree with its inertial parameters only
  Eigen::MatrixXd K_, K_inv_T_;
  Eigen::Index samples_ = 0;
  std::vector<double> A_;         // per sample: K^-T W_std, dof x inertial_, row-major
  Eigen::MatrixXd dq_M_, ddq_M_;  // dof x samples
};

/// A generated drive model compiled in: GeneratedDriveModel<modelgen::kr150::Model>, using the
/// generated kDof, kDriveParams, kDriveRegressorEntries, drive_param_names(),
/// drive_regressor(q, dq, ddq, Y), drive_torque_given_regressor(Y, theta, tau_M) and
/// drive_torque_jacobian_given_regressor(Y, theta, tau_M, J) (Y packed: its entries that are not
/// structurally zero; J kDof x kDriveParams, row-major). set_samples() stores the packed drive
/// regressor Y of every sample, the part of the model that does not depend on theta (samples x
/// kDriveRegressorEntries doubles: 3.3 MB for the KR150's 1540 samples, where the dense Y would
/// take 6.9 MB); torque() and torque_jacobian() then only read it, so they may run from several
/// threads at once.
template <class Generated>
class GeneratedDriveModel final : public DriveModel {
  static_assert(Generated::kFormatVersion == kGeneratedFormatVersion,
                "this generated model was made by a modelgen whose generated format differs "
                "from this runtime's: regenerate it with the modelgen of this runtime");
  static constexpr int kDof = Generated::kDof;
  static constexpr Eigen::Index kStride = Generated::kDriveRegressorEntries;

 public:
  GeneratedDriveModel()
      : names_(Generated::drive_param_names(),
               Generated::drive_param_names() + Generated::kDriveParams) {}

  int dof() const override { return kDof; }
  const std::vector<std::string>& param_names() const override { return names_; }
  void set_samples(const Eigen::MatrixXd& q, const Eigen::MatrixXd& dq,
                   const Eigen::MatrixXd& ddq) override {
    const Eigen::Index n = q.rows();
    if (q.cols() != dof() || dq.cols() != dof() || ddq.cols() != dof() || dq.rows() != n ||
        ddq.rows() != n) {
      throw std::invalid_argument("drive model: q, dq, ddq must be samples x " +
                                  std::to_string(dof()) + " matrices of equal size");
    }
    // Zero-filled before drive_regressor writes each sample: an entry it leaves unwritten (one
    // the generator found always zero) stays zero.
    Y_.assign(static_cast<std::size_t>(n * kStride), 0.0);
    double x[3 * kDof];  // one sample's q, dq, ddq, contiguous as the generated code reads them
    for (Eigen::Index s = 0; s < n; ++s) {
      for (int j = 0; j < kDof; ++j) {
        x[j] = q(s, j);
        x[kDof + j] = dq(s, j);
        x[2 * kDof + j] = ddq(s, j);
      }
      Generated::drive_regressor(x, x + kDof, x + 2 * kDof, regressor(s));
    }
    samples_ = n;
  }
  Eigen::Index num_samples() const override { return samples_; }
  void torque(Eigen::Index s, const double* theta, double* tau_M) const override {
    Generated::drive_torque_given_regressor(regressor(s), theta, tau_M);
  }
  void torque_jacobian(Eigen::Index s, const double* theta, double* tau_M,
                       double* J) const override {
    // J's entries that are zero for every sample are not written (the interface's contract:
    // the caller zeroes J once).
    Generated::drive_torque_jacobian_given_regressor(regressor(s), theta, tau_M, J);
  }

 private:
  double* regressor(Eigen::Index s) { return &Y_[static_cast<std::size_t>(s * kStride)]; }
  const double* regressor(Eigen::Index s) const {
    return &Y_[static_cast<std::size_t>(s * kStride)];
  }

  std::vector<std::string> names_;
  Eigen::Index samples_ = 0;
  std::vector<double> Y_;  // per sample: the packed Y, kDriveRegressorEntries values
};

}  // namespace modelgen
