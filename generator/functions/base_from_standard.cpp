// The regrouping relations beta = K p of the base parameters, one linear combination of
// standard parameters per base parameter.

#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_base_from_standard(BuildContext& context) {
  ExprGraph& graph = context.graph;
  FunctionDefinition definition;
  for (int b = 0; b < context.num_base(); ++b) {
    std::vector<ExprId> terms;
    for (const auto& [k, coefficient] : context.base.params[b].relation) {
      terms.push_back(graph.mul(graph.constant(coefficient), input_symbol(graph, "p_standard", k)));
    }
    definition.outputs.push_back(
        {element("beta", b), graph.add(terms), context.base.params[b].name});
  }
  return definition;
}

}  // namespace modelgen::gen
