// Inverse dynamics on the base parameters: Newton-Euler with each base parameter in place of the
// standard one it is built on and the absorbed parameters at zero (Gautier & Briot eq. 4).

#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_inverse_dynamics(BuildContext& context) {
  return {vector_outputs("tau", derive_inverse_dynamics(context.graph, context.tree(),
                                                        base_parameter_inputs(context)))};
}

}  // namespace modelgen::gen
