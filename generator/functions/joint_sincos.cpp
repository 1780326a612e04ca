// sin and cos of every joint variable, for the _sincos variants of the other functions.

#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_joint_sincos(BuildContext& context) {
  FunctionDefinition definition;
  for (int i = 0; i < context.dof(); ++i) {
    definition.outputs.push_back({element("sin_q", i), context.symbols.sin_q[i], ""});
    definition.outputs.push_back({element("cos_q", i), context.symbols.cos_q[i], ""});
  }
  return definition;
}

}  // namespace modelgen::gen
