// Orocos KDL as an independent oracle for modelgen's dynamics: inverse dynamics of a serial
// RigidBodyTree by KDL's ChainIdSolver_RNE plus the drive terms KDL does not model, and the
// random physical parameters and joint states to compare on. KDL is included only by
// kdl_oracle.cpp, so users of this header need not see its headers.
#pragma once

#include <Eigen/Core>

#include "modelgen/model/robot_model.hpp"
#include "modelgen/model/rigid_body_tree.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::test {

/// True if every body's parent is the body before it (body 0 on the base): the only shape a
/// KDL::Chain can take. An empty tree is serial.
bool is_serial(const RigidBodyTree& tree);

/// Position of an inertial parameter in XX XY XZ YY YZ ZZ MX MY MZ M order (the order of
/// modelgen::standard_from_inertial), -1 for a drive parameter.
int inertial_slot(ParamKind kind);

/// Joint torques (N m, N for prismatic joints), tree.dof entries in modelgen's dof order, by
/// KDL::ChainIdSolver_RNE on a chain built from `tree` and `p`, plus the drive terms KDL lacks
/// (Gautier & Briot eq. 3: Ia ddq + Fv dq + Fc sign(dq) + OFF; asymmetric friction Bona &
/// Curatella eq. 2). `q`, `dq`, `ddq` have tree.dof entries in dof order (rad, rad/s, rad/s^2 or
/// m, m/s, m/s^2); `p` has tree.params.size() entries in tree.params order (SI units). No
/// external wrenches; gravity is tree.gravity. The chain is rebuilt on every call.
/// Throws std::invalid_argument for a non-serial tree, wrong input sizes, or a body with first
/// moments but zero mass; std::runtime_error if the KDL solver fails.
Eigen::VectorXd kdl_inverse_dynamics(const RigidBodyTree& tree, const Eigen::VectorXd& q,
                                     const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq,
                                     const Eigen::VectorXd& p);

/// The joint-space inertia matrix of the rigid bodies alone (no drive inertias), dof x dof in
/// modelgen's dof order, by KDL::ChainDynParam::JntToMass. Same chain and exceptions as above.
Eigen::MatrixXd kdl_rigid_body_mass_matrix(const RigidBodyTree& tree, const Eigen::VectorXd& q,
                                           const Eigen::VectorXd& p);

/// Joint accelerations of the rigid bodies alone (no drive terms) under joint torques `tau`, by
/// KDL::ChainFdSolver_RNE, in dof order. Same chain and exceptions as above.
Eigen::VectorXd kdl_rigid_body_forward_dynamics(const RigidBodyTree& tree, const Eigen::VectorXd& q,
                                                const Eigen::VectorXd& dq,
                                                const Eigen::VectorXd& tau,
                                                const Eigen::VectorXd& p);

/// A uniformly distributed random rotation matrix (Shoemake's random unit quaternion).
Eigen::Matrix3d random_rotation(Random& rng);

/// A physically meaningful standard parameter vector, tree.params.size() entries in tree.params
/// order. Per body: mass uniform in [0.5, 10] kg, centre of mass in [-0.3, 0.3]^3 m, inertia about
/// it R diag(a, b, c) R^T kg m^2 with R a random rotation and a, b, c > 0 strictly satisfying the
/// triangle inequality; returned about the body frame origin. Drive parameters uniform in [0, 2].
Eigen::VectorXd random_physical_parameters(const RigidBodyTree& tree, Random& rng);

/// Joint positions, velocities and accelerations; tree.dof entries each, in dof order.
struct JointState {
  Eigen::VectorXd q, dq, ddq;
};

/// A random state of `model`: q uniform within the joint limits where both are given (by
/// model.joints, index-aligned with model.tree.bodies), else in [-pi, pi] rad (revolute) or
/// [-0.5, 0.5] m (prismatic); dq uniform in [-3, 3] rad/s or m/s, ddq in [-10, 10] rad/s^2 or
/// m/s^2.
JointState random_state(const modelgen::RobotModel& model, Random& rng);

}  // namespace modelgen::test
