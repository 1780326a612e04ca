// Symbolic Newton-Euler on the RigidBodyTree (Khalil-Kleinfinger formulation: inertia about the
// frame origin and first moments MS keep every force linear in the standard parameters).
// Forward recursion of velocities and accelerations, backward recursion of wrenches; the
// standard regressor falls out column by column (Gautier & Briot eq. 2-4).
#pragma once

#include <array>
#include <vector>

#include "generator/dynamics/symbolic_vectors.hpp"
#include "generator/symbolic/expr.hpp"
#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen::gen {

/// The leaves of the generated functions: inputs by array index, and sin/cos/sign of the joint
/// variables named after the 1-based joint number (s1, c1, sg1, ...).
struct SymbolicInputs {
  std::vector<ExprId> q, dq, ddq;      ///< per dof
  std::vector<ExprId> sin_q, cos_q;    ///< per dof (revolute joints use them)
  std::vector<ExprId> sign_dq;         ///< sign(dq), 0 at rest
  std::vector<ExprId> positive_dq;     ///< 1 if dq > 0
  std::vector<ExprId> negative_dq;     ///< 1 if dq < 0
  std::vector<ExprId> p;               ///< standard parameters p[k]
};

SymbolicInputs make_symbolic_inputs(ExprGraph& graph, const RigidBodyTree& tree);

/// The forward recursion: pose of each body frame in its antecedent and its motion, every
/// vector in the body's own frame. dv includes gravity (dv0 = -g); v does not.
struct SymbolicMotion {
  std::vector<M3> R;  ///< antecedent <- body rotation
  std::vector<V3> p;  ///< body origin in the antecedent frame
  std::vector<V3> w, dw, v, dv;  ///< angular velocity and acceleration, origin velocity and acceleration
  /// The products of w's components, each shared: w0 w0, w1 w1, w2 w2, w0 w1, w0 w2, w1 w2.
  std::vector<std::array<ExprId, 6>> ww;
  /// U = [dw]x + [w]x [w]x (row-major, entries shared), so that dw x r + w x (w x r) = U r:
  /// Khalil & Kleinfinger's U_j, built once per body from dw and ww and read by the body's
  /// forces and inertia moments (inverse dynamics and standard regressor alike) and by its
  /// children's accelerations.
  std::vector<M3> U;
};

SymbolicMotion derive_motion(ExprGraph& graph, const RigidBodyTree& tree, const SymbolicInputs& in);

/// The standard regressor W, row-major dof x params: tau = W p (Gautier & Briot eq. 2).
std::vector<ExprId> derive_standard_regressor(ExprGraph& graph, const RigidBodyTree& tree,
                                              const SymbolicInputs& in);

/// Joint torques tau(q, dq, ddq, p), one per dof, by the recursive Newton-Euler with the
/// standard parameters as symbols.
std::vector<ExprId> derive_inverse_dynamics(ExprGraph& graph, const RigidBodyTree& tree,
                                            const SymbolicInputs& in);

}  // namespace modelgen::gen
