// Standard regressor of the inverse dynamic identification model (Gautier & Briot eq. 2):
// tau = W p, one column per standard parameter, from the symbolic Newton-Euler.

#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_idim_regressor_standard(BuildContext& context) {
  const std::vector<ExprId> W =
      derive_standard_regressor(context.graph, context.tree(), context.symbols);
  const int columns = context.num_params();
  return {row_major_outputs(
      "W", context.dof(), columns, [&](int i, int k) { return W[i * columns + k]; },
      [&](int k) { return context.tree().params[k].name; })};
}

}  // namespace modelgen::gen
