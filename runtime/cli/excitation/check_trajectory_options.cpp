// modelid check-trajectory's and check's options, declared once
// (modelgen/model/option_table.hpp).

#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/q_limit_option.hpp"

namespace modelgen::internal {

const CommandSpec& check_trajectory_spec() {
  static const CommandSpec spec = modelid_command(
      "check-trajectory",
      "the use of every joint limit (and of the effort limits, from the a-priori inertials) by a "
      "Fourier excitation",
      {robot_option(),
       {.name = "--trajectory",
        .value = "TRAJ.yaml",
        .help = "the Fourier excitation",
        .required = true},
       {.name = "--ddq-limit",
        .value = "A[,A2,...]",
        .help = "acceleration limits the description lacks (one or one per joint)",
        .unit = "rad/s^2 or m/s^2"},
       q_limit_option_spec(),
       {.name = "--plot",
        .value = "DIR",
        .help = "write DIR/trajectory.svg: q, dq, ddq per joint against the limits"}});
  return spec;
}

const CommandSpec& check_spec() {
  static const CommandSpec spec = [] {
    CommandSpec spec = modelid_command("check", "load a model and print its sizes", {});
    spec.operands = "ROBOT";
    return spec;
  }();
  return spec;
}

}  // namespace modelgen::internal
