// d tau / d(q, dq, ddq) of the base inverse dynamics, the state part of B in Bona & Curatella
// eq. 15-16, from the same DAG: derivatives of Newton-Euler intermediates stay intermediates.
// The first row names the state variable of each column.

#include "generator/functions/build_context.hpp"
#include "generator/symbolic/derivative.hpp"

namespace modelgen::gen {

FunctionDefinition build_inverse_dynamics_state_jacobian(BuildContext& context) {
  const std::vector<ExprId> tau =
      derive_inverse_dynamics(context.graph, context.tree(), base_parameter_inputs(context));
  const std::vector<ExprId> J = jacobian(context.graph, tau, state_symbols(context.symbols));
  const int n = context.dof();
  return {row_major_outputs(
      "J", n, 3 * n, [&](int i, int k) { return J[i * 3 * n + k]; },
      [&](int k) { return state_name(k, n); })};
}

}  // namespace modelgen::gen
