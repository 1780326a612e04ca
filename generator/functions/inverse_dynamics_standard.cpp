// Inverse dynamics on the standard parameters: the recursive Newton-Euler, flattened.

#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_inverse_dynamics_standard(BuildContext& context) {
  return {vector_outputs("tau",
                         derive_inverse_dynamics(context.graph, context.tree(), context.symbols))};
}

}  // namespace modelgen::gen
