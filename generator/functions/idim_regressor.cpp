// Regressor on the base parameters: the standard regressor restricted to the independent
// columns, one per base parameter (Gautier & Briot eq. 4-6).

#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_idim_regressor(BuildContext& context) {
  const std::vector<ExprId> W =
      derive_standard_regressor(context.graph, context.tree(), context.symbols);
  const std::vector<BaseParameter>& base = context.base.params;
  const int standard_columns = context.num_params();
  return {row_major_outputs(
      "W", context.dof(), context.num_base(),
      [&](int i, int b) { return W[i * standard_columns + base[b].standard_index]; },
      [&](int b) { return base[b].name; })};
}

}  // namespace modelgen::gen
