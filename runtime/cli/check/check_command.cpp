// modelid check ROBOT: loads a description or a compiled-in model and prints its sizes.

#include <iostream>

#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/model_source.hpp"

namespace modelgen::internal {

int run_check(const CommandLine& args) {
  if (args.positional.size() != 1) throw UsageError{"check takes one ROBOT"};
  const ModelSource source =
      load_model_source(args.positional[0], description_options(args), DescriptionModel::kNumeric);
  std::cout << source.model->name() << ": " << source.model->dof() << " dof, "
            << source.model->num_standard_params() << " standard and "
            << source.model->num_base_params() << " base parameters\n";
  return 0;
}

}  // namespace modelgen::internal
