// Orocos KDL's recursive Newton-Euler prepared once for timing: a RigidBodyTree with standard
// parameters becomes a KDL::Chain and a ChainIdSolver_RNE that live as long as this object, so
// the benchmark loop times CartToJnt alone (tests/support/kdl_oracle.cpp rebuilds both per call).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <kdl/chain.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/jntarray.hpp>

#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen::bench {

/// How moving bodies become KDL segments.
enum class KdlChainShape {
  /// One segment per body, as kdl_parser builds it from a URDF: the joint placed by the body's
  /// fixed transform, tip at the body frame, the body's inertia. The fair comparison.
  kSegmentPerBody,
  /// tests/support/kdl_oracle.cpp's form: a fixed segment carrying the body's fixed transform,
  /// then a jointed segment with identity tip and the body's inertia (twice the segments).
  kFixedThenJoint,
};

/// A KDL chain and its inverse dynamics solver, built once. Not copyable or movable: the solver
/// keeps a reference to the chain.
class KdlRne {
 public:
  /// `tree` must be serial (every body's parent the body before it); `p` has tree.params.size()
  /// standard parameters in tree.params order (SI units). Drive parameters (Ia, Fv, ...) are
  /// ignored: KDL has no model for them. Gravity is tree.gravity.
  /// Throws std::invalid_argument for a non-serial tree, a wrong size of `p`, or a body with
  /// first moments but zero mass.
  KdlRne(const RigidBodyTree& tree, const Eigen::VectorXd& p, KdlChainShape shape);
  KdlRne(const KdlRne&) = delete;
  KdlRne& operator=(const KdlRne&) = delete;

  /// `v` (tree.dof entries, modelgen dof order) reordered into KDL's joint order.
  KDL::JntArray to_kdl(const Eigen::VectorXd& v) const;

  /// Joint torques of the rigid bodies alone (N m or N), KDL joint order; no external wrenches.
  /// Returns KDL's status (negative on failure). Allocates nothing.
  int solve(const KDL::JntArray& q, const KDL::JntArray& dq, const KDL::JntArray& ddq,
            KDL::JntArray& tau) {
    return solver_.CartToJnt(q, dq, ddq, no_external_, tau);
  }

  /// Convenience for checks: torques in modelgen dof order. Throws std::runtime_error if KDL fails.
  Eigen::VectorXd inverse_dynamics(const Eigen::VectorXd& q, const Eigen::VectorXd& dq,
                                   const Eigen::VectorXd& ddq);

  unsigned num_joints() const { return chain_.getNrOfJoints(); }
  /// The chain, for KDL's other solvers (forward dynamics).
  const KDL::Chain& chain() const { return chain_; }
  unsigned num_segments() const { return chain_.getNrOfSegments(); }

 private:
  KDL::Chain chain_;                   // declared before solver_, which refers to it
  std::vector<int> dof_of_kdl_joint_;  // modelgen dof index of each KDL joint, in chain order
  KDL::ChainIdSolver_RNE solver_;
  KDL::Wrenches no_external_;
};

}  // namespace modelgen::bench
