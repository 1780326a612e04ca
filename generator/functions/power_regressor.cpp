// Power regressor of the power model on the base parameters: the base columns of the standard
// dh(q, dq, ddq) = d h / dt plus the friction and offset power (Gautier & Briot eq. 9-10).

#include "generator/dynamics/power_model.hpp"
#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_power_regressor(BuildContext& context) {
  ExprGraph& graph = context.graph;
  const std::vector<ExprId> h = derive_energy_regressor(graph, context.tree(), context.symbols);
  const std::vector<ExprId> dh = derive_power_regressor(graph, context.tree(), context.symbols, h);
  FunctionDefinition definition;
  for (int b = 0; b < context.num_base(); ++b) {
    const BaseParameter& parameter = context.base.params[b];
    definition.outputs.push_back({element("dh", b), dh[parameter.standard_index], parameter.name});
  }
  return definition;
}

}  // namespace modelgen::gen
