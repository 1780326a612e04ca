// modelid check-trajectory's and check's options, declared once
// (modelgen/model/option_table.hpp).

#include "runtime/cli/common/commands.hpp"

namespace modelgen::internal {

namespace {

CommandSpec make_check_trajectory_spec() {
  CommandSpec spec{.program = "modelid",
                   .name = "check-trajectory",
                   .summary =
                       "the use of every joint limit (and of the effort limits, from the "
                       "a-priori inertials) by a Fourier excitation"};
  spec.options = {
      {.name = "--robot",
       .value = "ROBOT",
       .help = "the description file or shipped model",
       .required = true},
      {.name = "--trajectory",
       .value = "TRAJ.yaml",
       .help = "the Fourier excitation",
       .required = true},
      {.name = "--ddq-limit",
       .value = "A[,A2,...]",
       .help = "acceleration limits the description lacks (one or one per joint)",
       .unit = "rad/s^2 or m/s^2"},
      {.name = "--plot",
       .value = "DIR",
       .help = "write DIR/trajectory.svg: q, dq, ddq per joint against the limits"},
  };
  const std::vector<OptionSpec> common = common_options();
  spec.options.insert(spec.options.end(), common.begin(), common.end());
  return spec;
}

CommandSpec make_check_spec() {
  CommandSpec spec{.program = "modelid",
                   .name = "check",
                   .summary = "load a model and print its sizes",
                   .operands = "ROBOT"};
  spec.options = common_options();
  return spec;
}

}  // namespace

const CommandSpec& check_trajectory_spec() {
  static const CommandSpec spec = make_check_trajectory_spec();
  return spec;
}

const CommandSpec& check_spec() {
  static const CommandSpec spec = make_check_spec();
  return spec;
}

}  // namespace modelgen::internal
