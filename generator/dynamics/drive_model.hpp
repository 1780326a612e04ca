// The nonlinear drive model F of Swevers et al. 2002 (eq. 12): motor torques from the joint
// motion through the rigid-body dynamics (eq. 1), the coupling (eq. 9-10), the transmission
// efficiency (eq. 8, inverted) and the motor inertia and friction (eq. 5-7), with the
// parameters theta of eq. 14 as symbols, so that its Jacobians come from the same DAG.
//
// All quantities are on the link side (the paper divides motor angles by the gear ratios); K is
// the description's motor_from_joint (dq_M = K dq, tau_G = K^T tau'_G), V = K^-1. Per sample:
//   tau_G   = W_std(q, dq, ddq) p                          (eq. 1; inertial parameters only)
//   tau'_G  = V^T tau_G = K^-T tau_G                      (eq. 10)
//   dq_M    = K dq,  ddq_M = K ddq                          (eq. 9)
//   tau_T_i = tau'_G_i / Rz_i  if tau'_G_i dq_M_i > 0        (eq. 8 solved for its input:
//             tau'_G_i Rz_i    if tau'_G_i dq_M_i < 0         the motor drives, or the load does)
//   tau_M_i = tau_T_i + JM_i ddq_M_i + Rv_i dq_M_i + Rc_i sign(dq_M_i)             (eq. 7)
// With s_i = sign(tau'_G_i dq_M_i), tau_T_i = tau'_G_i c_i, c_i = (1 + s_i)/2 / Rz_i +
// (1 - s_i)/2 Rz_i: at the switch (s_i = 0, a set of measure zero) this is the mean of both
// branches, tau'_G_i (1/Rz_i + Rz_i) / 2, which is what the sign-based formula gives; eq. 8
// itself leaves it open.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "generator/dynamics/newton_euler.hpp"
#include "generator/symbolic/expr.hpp"
#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen::gen {

/// The parameters theta (Swevers eq. 14) as symbols theta[0], theta[1], ..., in this order: the
/// inertial standard parameters of the tree (XXj XYj XZj YYj YZj ZZj MXj MYj MZj Mj of every
/// body, fixed bodies included, in the order of tree.params and with their names), then per
/// moving joint, in dof order, JMj Rvj Rcj Rzj (rotor inertia, viscous and Coulomb friction of
/// the motor, transmission efficiency), j the number of the joint's body as in its Iaj name.
struct DriveParameters {
  std::vector<std::string> names;
  std::vector<ExprId> theta;
  /// For each inertial entry of theta (the first standard_index.size() ones), its index in
  /// tree.params.
  std::vector<int> standard_index;
  std::vector<ExprId> JM, Rv, Rc, Rz;  ///< per dof, entries of theta
};

DriveParameters make_drive_parameters(ExprGraph& graph, const RigidBodyTree& tree);

/// The standard parameter vector of the rigid-body part: theta's inertial entries in their
/// places, zero for the drive terms of the standard list (Ia, Fv, Fc, OFF, the asymmetric
/// friction and Iam, Fvm, Fcm), which JM, Rv, Rc and Rz replace.
std::vector<ExprId> rigid_body_parameters(ExprGraph& graph, const RigidBodyTree& tree,
                                          const DriveParameters& parameters);

/// V = K^-1 (Swevers eq. 9: q_G = V q_M) for K = motor_from_joint, dof x dof. Throws
/// std::logic_error if K has the wrong size or is singular (the description loaders reject such
/// a coupling before this is reached).
Eigen::MatrixXd joint_from_motor(const Eigen::MatrixXd& motor_from_joint, int dof);

/// The drive model on given rigid-body torques tau_G (any expressions, one per dof).
struct DriveTorques {
  std::vector<ExprId> tau_out;     ///< tau'_G = V^T tau_G (eq. 10), shared
  std::vector<ExprId> efficiency;  ///< c_i of the file comment (eq. 8), shared
  std::vector<ExprId> tau_M;       ///< motor torques of eq. 7
};

DriveTorques derive_drive_torques(ExprGraph& graph, const Eigen::MatrixXd& motor_from_joint,
                                  const SymbolicInputs& in, const DriveParameters& parameters,
                                  const std::vector<ExprId>& tau_G);

/// One motor i: tau_M_i of eq. 7 from the net actuator torque tau'_G_i (`tau_out`), the motor
/// velocity dq_M_i, its sign and the acceleration ddq_M_i; `efficiency` receives c_i (shared).
ExprId motor_torque(ExprGraph& graph, const DriveParameters& parameters, int i, ExprId tau_out,
                    ExprId dq_M, ExprId sign_dq_M, ExprId ddq_M, ExprId* efficiency);

/// The regressor Y of the drive model with unit efficiencies (Swevers section 3.2's linear
/// model), row-major dof x theta.size(): tau_M = Y theta whenever every Rz is 1. Row i holds
/// V^T W (eq. 10) in the inertial columns, ddq_M_i, dq_M_i and sign(dq_M_i) (eq. 5-7, 9) in the
/// columns of JM_i, Rv_i and Rc_i, and zero elsewhere (the Rz columns too). W is the standard
/// regressor, row-major dof x tree.params (any expressions: symbolic, or input symbols).
/// Everything in Y is independent of theta, so a fit can evaluate it once per sample.
std::vector<ExprId> derive_drive_regressor(ExprGraph& graph,
                                           const Eigen::MatrixXd& motor_from_joint,
                                           const SymbolicInputs& in,
                                           const DriveParameters& parameters,
                                           const std::vector<ExprId>& W);

/// tau_M of eq. 7 from the drive regressor Y (layout of derive_drive_regressor, any
/// expressions) and theta: tau'_G_i = sum over the inertial k of Y(i, k) theta_k (eq. 10), the
/// motor motion read from the JM, Rv and Rc columns, then motor_torque.
std::vector<ExprId> drive_torques_from_regressor(ExprGraph& graph,
                                                 const DriveParameters& parameters,
                                                 const std::vector<ExprId>& Y);

}  // namespace modelgen::gen
