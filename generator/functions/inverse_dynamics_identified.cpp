// Inverse dynamics on the identified base parameters (modelgen --params): a call to
// inverse_dynamics with the constant array of the estimate, so that a controller needs no
// estimate file at run time and computes exactly what inverse_dynamics computes on those values.

#include "generator/emit/identified_constants.hpp"
#include "generator/functions/build_context.hpp"

namespace modelgen::gen {

FunctionDefinition build_inverse_dynamics_identified(BuildContext& context) {
  FunctionDefinition definition;
  definition.prologue = [scalars = context.scalars](Scalar scalar) {
    return std::vector<std::string>{call(
        "inverse_dynamics", "q, dq, ddq, " + identified_base_array(scalar, scalars) + ", tau")};
  };
  definition.outputs_written_by_call = true;
  return definition;
}

}  // namespace modelgen::gen
