// The joint-space inertia matrix M(q) on the base parameters. The rigid bodies' part by
// composite rigid bodies (generator/dynamics/composite_inertia.cpp) on the base parameters
// substituted into the standard ones; the drive inertias (Ia, and the rotor inertia of a motor
// driving several joints) as d tau / d ddq of the Newton-Euler with only the drive parameters,
// at rest and without gravity, so only those terms are derived at all. The inverse dynamics is
// tau = M(q) ddq + (velocity, gravity, friction and offset terms, none of which depends on
// ddq). The composite-body M took about 30 % fewer operations than d tau / d ddq of the whole
// Newton-Euler (TX-40: 399 mul and 300 add before).

#include <algorithm>

#include "generator/dynamics/composite_inertia.hpp"
#include "generator/functions/build_context.hpp"
#include "generator/symbolic/derivative.hpp"

namespace modelgen::gen {

std::vector<ExprId> base_mass_matrix(BuildContext& context) {
  ExprGraph& graph = context.graph;
  const SymbolicInputs base = base_parameter_inputs(context);
  std::vector<ExprId> M = derive_rigid_body_mass_matrix(graph, context.tree(), base);
  RigidBodyTree without_gravity = context.tree();
  without_gravity.gravity = {0, 0, 0};
  SymbolicInputs drives_at_rest = base;
  for (std::vector<ExprId>* velocity_terms :
       {&drives_at_rest.dq, &drives_at_rest.sign_dq, &drives_at_rest.positive_dq,
        &drives_at_rest.negative_dq}) {
    std::fill(velocity_terms->begin(), velocity_terms->end(), graph.zero());
  }
  for (std::size_t k = 0; k < context.tree().params.size(); ++k) {
    if (is_inertial(context.tree().params[k].kind)) drives_at_rest.p[k] = graph.zero();
  }
  const std::vector<ExprId> tau = derive_inverse_dynamics(graph, without_gravity, drives_at_rest);
  const std::vector<ExprId> drive = jacobian(graph, tau, drives_at_rest.ddq);
  for (std::size_t e = 0; e < M.size(); ++e) M[e] = graph.add(M[e], drive[e]);
  return M;
}

FunctionDefinition build_mass_matrix(BuildContext& context) {
  const std::vector<ExprId> M = base_mass_matrix(context);
  const int n = context.dof();
  // Symmetric by construction: the lower triangle takes the upper's values.
  return {row_major_outputs("M", n, n,
                            [&](int i, int k) { return M[std::min(i, k) * n + std::max(i, k)]; })};
}

}  // namespace modelgen::gen
