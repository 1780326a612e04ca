// The drive chain between motors and joints: gear ratios, the coupling matrix, motor torque
// constants and encoder offsets. One type for the description (as the user wrote it, for
// `modelgen describe` and generated constants) and for the runtime (motor-side data, currents).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace modelgen {

/// How motor and joint quantities relate. Stored in one canonical form, K = motor_from_joint
/// (dq_motor = K dq_joint, Gautier & Briot eq. 25; tau_joint = K^T tau_motor by power balance).
/// The Swevers form (eq. 9: q_G = V q_M with q_M the motor angles divided by the gear ratios)
/// converts as K = diag(ratio) V^-1.
struct DriveChain {
  Eigen::MatrixXd motor_from_joint;  ///< K, dof x dof; identity scaled by ratio when no coupling
  /// Motor torque constant per motor, N m/A (tau_motor = k i); 0 where not given.
  Eigen::VectorXd torque_constant;
  /// Joint position at motor position zero, per joint: q = K^-1 q_motor + joint_offset.
  Eigen::VectorXd joint_offset;

  // As written in the description (empty for a drive chain made at run time).
  std::vector<double> ratio;            ///< gear ratio per moving joint; empty when not given
  std::string coupling_form;            ///< "joint_from_motor", "motor_from_joint" or empty
  Eigen::MatrixXd coupling_as_written;  ///< the matrix the user gave (block of coupled joints)
  std::vector<int> coupled_joints;      ///< 0-based dof indices the written block acts on

  bool has_coupling() const { return !coupling_form.empty(); }

  /// The identity drive chain of `dof` joints (motor and joint sides coincide), no torque
  /// constants, no offsets.
  static DriveChain identity(int dof) {
    DriveChain chain;
    chain.motor_from_joint = Eigen::MatrixXd::Identity(dof, dof);
    chain.torque_constant = Eigen::VectorXd::Zero(dof);
    chain.joint_offset = Eigen::VectorXd::Zero(dof);
    return chain;
  }
};

}  // namespace modelgen
