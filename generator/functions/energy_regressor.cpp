// Energy regressor of the power model on the base parameters: the base columns of the
// standard h(q, dq) (Gautier & Briot eq. 8).

#include "generator/dynamics/power_model.hpp"
#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_energy_regressor(BuildContext& context) {
  const std::vector<ExprId> h =
      derive_energy_regressor(context.graph, context.tree(), context.symbols);
  FunctionDefinition definition;
  for (int b = 0; b < context.num_base(); ++b) {
    const BaseParameter& parameter = context.base.params[b];
    definition.outputs.push_back({element("h", b), h[parameter.standard_index], parameter.name});
  }
  return definition;
}

}  // namespace modelgen::gen
