// modelid validate's options, declared once (modelgen/model/option_table.hpp).

#include "runtime/cli/common/commands.hpp"

namespace modelgen::internal {

namespace {

CommandSpec make_validate_spec() {
  CommandSpec spec{.program = "modelid",
                   .name = "validate",
                   .summary =
                       "an estimate simulated under the controller along a closed-loop "
                       "record, compared with it"};
  spec.options = {
      {.name = "--robot",
       .value = "ROBOT",
       .help = "the description file or shipped model",
       .required = true},
      {.name = "--params",
       .value = "EST.json",
       .help = "the estimate to validate",
       .required = true},
      {.name = "--controller",
       .value = "C.yaml",
       .help = "the joint controller the record was made under",
       .required = true},
      {.name = "--data",
       .value = "FILE",
       .help = "the closed-loop record (t, q, tau, qr)",
       .required = true},
      {.name = "--plot",
       .value = "DIR",
       .help = "write the compared positions and torques "
               "into DIR"},
  };
  const std::vector<OptionSpec> common = common_options();
  spec.options.insert(spec.options.end(), common.begin(), common.end());
  return spec;
}

}  // namespace

const CommandSpec& validate_spec() {
  static const CommandSpec spec = make_validate_spec();
  return spec;
}

}  // namespace modelgen::internal
