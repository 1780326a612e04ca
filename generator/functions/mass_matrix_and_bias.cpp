// What forward dynamics needs at one state, in one function: the joint-space inertia matrix M(q)
// (base_mass_matrix, as mass_matrix builds it) and the bias h = tau(q, dq, ddq = 0), both on the
// base parameters. One body shares what both read (the joints' sines and cosines, only of the
// joints either uses, and the products of the rotations), and ddq = 0 folds the acceleration terms
// out of h while it is built instead of multiplying them by zero at run time.

#include <algorithm>

#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_mass_matrix_and_bias(BuildContext& context) {
  ExprGraph& graph = context.graph;
  const int n = context.dof();
  const std::vector<ExprId> M = base_mass_matrix(context);
  SymbolicInputs no_acceleration = base_parameter_inputs(context);
  std::fill(no_acceleration.ddq.begin(), no_acceleration.ddq.end(), graph.zero());
  const std::vector<ExprId> h = derive_inverse_dynamics(graph, context.tree(), no_acceleration);
  FunctionDefinition definition{row_major_outputs(
      "M", n, n, [&](int i, int k) { return M[std::min(i, k) * n + std::max(i, k)]; })};
  for (FunctionOutput& output : vector_outputs("h", h)) {
    definition.outputs.push_back(std::move(output));
  }
  return definition;
}

}  // namespace modelgen::gen
