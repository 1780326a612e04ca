// The power identification model (Gautier & Briot eq. 8-12): the total energy H = h p and the
// power dq . tau = dh p, with dh = d h / dt plus the friction and offset power. It shares the
// parameters of the inverse dynamic model exactly.
#pragma once

#include <vector>

#include "generator/dynamics/newton_euler.hpp"
#include "generator/symbolic/expr.hpp"
#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen::gen {

/// h(q, dq): one entry per standard parameter, H = sum_k h[k] p[k] (kinetic energy of links
/// and drives, potential energy in the gravity field, zero at the base origin).
std::vector<ExprId> derive_energy_regressor(ExprGraph& graph, const RigidBodyTree& tree,
                                            const SymbolicInputs& in);

/// dh(q, dq, ddq): d h / dt, plus the power of friction and offsets (Fv: dq^2, Fc: |dq|,
/// OFF: dq, ...), so that dq . tau = sum_k dh[k] p[k] (Gautier & Briot eq. 9-10).
std::vector<ExprId> derive_power_regressor(ExprGraph& graph, const RigidBodyTree& tree,
                                           const SymbolicInputs& in,
                                           const std::vector<ExprId>& energy_regressor);

}  // namespace modelgen::gen
