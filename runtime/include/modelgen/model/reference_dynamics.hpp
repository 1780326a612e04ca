// The numeric reference: a recursive Newton-Euler inverse dynamics written for clarity, the
// oracle every generated function is diff-tested against. Works on any RigidBodyTree (trees,
// revolute and prismatic joints) with the standard parameters of Gautier & Briot eq. 3.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen {

class ReferenceDynamics {
 public:
  /// Validates the tree (see validate()); throws std::invalid_argument if it is malformed.
  explicit ReferenceDynamics(RigidBodyTree tree);

  const RigidBodyTree& tree() const { return tree_; }
  int dof() const { return tree_.dof; }
  int num_params() const { return static_cast<int>(tree_.params.size()); }

  /// Joint torques (N m, N for prismatic joints), size dof, for joint positions q (rad or m),
  /// velocities dq and accelerations ddq (each size dof) and standard parameters p (size
  /// num_params(), in tree().params order). Includes gravity, drive inertia, friction and offset.
  /// Coulomb friction uses sign(dq) with sign(0) = 0. Throws std::invalid_argument on wrong sizes.
  Eigen::VectorXd inverse_dynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                                   const Eigen::VectorXd& ddq, const Eigen::VectorXd& p) const;

  /// The standard regressor W (dof x num_params, column k belongs to tree().params[k]) with
  /// inverse_dynamics(q, dq, ddq, p) == W * p for every p. Built column by column from
  /// inverse_dynamics calls with unit parameter vectors.
  Eigen::MatrixXd standard_regressor(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                                     const Eigen::VectorXd& ddq) const;

  /// Kinetic energy of the links and drives (J), drive inertia counted as Ia dq^2 / 2.
  double kinetic_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                        const Eigen::VectorXd& p) const;

  /// Potential energy in the gravity field (J), zero at the base origin.
  double potential_energy(const Eigen::VectorXd& q, const Eigen::VectorXd& p) const;

  /// Pose of every body frame in the base frame, one per tree().bodies entry.
  std::vector<Frame> forward_kinematics(const Eigen::VectorXd& q) const;

 private:
  RigidBodyTree tree_;
};

}  // namespace modelgen
