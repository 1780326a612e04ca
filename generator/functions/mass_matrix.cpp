// The joint-space inertia matrix M(q) on the base parameters. The inverse dynamics is
// tau = M(q) ddq + (velocity, gravity, friction and offset terms, none of which depends on ddq),
// so M = d tau / d ddq of the Newton-Euler on the base parameters, taken at dq = 0 and without
// gravity so that only the inertial terms are derived at all. Drive inertias (Ia, and the rotor
// inertia of a motor driving several joints) are inertial terms and stay in M. Only the upper
// triangle is derived; the lower one is the same values.

#include <algorithm>

#include "generator/functions/build_context.hpp"
#include "generator/symbolic/derivative.hpp"

namespace modelgen::gen {

FunctionDefinition build_mass_matrix(BuildContext& context) {
  ExprGraph& graph = context.graph;
  RigidBodyTree without_gravity = context.tree();
  without_gravity.gravity = {0, 0, 0};
  SymbolicInputs at_rest = base_parameter_inputs(context);
  for (std::vector<ExprId>* velocity_terms :
       {&at_rest.dq, &at_rest.sign_dq, &at_rest.positive_dq, &at_rest.negative_dq}) {
    std::fill(velocity_terms->begin(), velocity_terms->end(), graph.zero());
  }
  const std::vector<ExprId> tau = derive_inverse_dynamics(graph, without_gravity, at_rest);
  const std::vector<ExprId> M = jacobian(graph, tau, at_rest.ddq);
  const int n = context.dof();
  // M is symmetric, but the derivatives of the two triangles are different expressions of one
  // value: the lower triangle takes the upper's, and is not computed a second time.
  return {row_major_outputs("M", n, n,
                            [&](int i, int k) { return M[std::min(i, k) * n + std::max(i, k)]; })};
}

}  // namespace modelgen::gen
