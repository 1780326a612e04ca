// The joint-space inertia matrix by composite rigid bodies (Featherstone's CRBA in Khalil &
// Kleinfinger's customized form): the inertial parameters of each subtree gathered into its
// root body's frame once, then column j of M is the wrench a unit acceleration of joint j asks
// of its composite body, carried towards the base and read on each joint on the way.
#pragma once

#include <vector>

#include "generator/dynamics/newton_euler.hpp"
#include "generator/symbolic/expr.hpp"
#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen::gen {

/// M(q) of the rigid bodies alone (no drive inertias), dof x dof row-major, symmetric, from
/// the inertial parameters in.p (standard ones, or base ones substituted in them) and in.q,
/// in.sin_q, in.cos_q; velocities, accelerations and gravity are not read.
std::vector<ExprId> derive_rigid_body_mass_matrix(ExprGraph& graph, const RigidBodyTree& tree,
                                                  const SymbolicInputs& in);

}  // namespace modelgen::gen
