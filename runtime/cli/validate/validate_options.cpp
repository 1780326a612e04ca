// modelid validate's options, declared once (modelgen/model/option_table.hpp).

#include "runtime/cli/common/commands.hpp"

namespace modelgen::internal {

const CommandSpec& validate_spec() {
  static const CommandSpec spec = modelid_command(
      "validate",
      "an estimate simulated under the controller along a closed-loop record, compared with it",
      {robot_option(),
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
       {.name = "--trajectory",
        .value = "TRAJ.yaml",
        .help = "the Fourier excitation of the record: its period and top harmonic give the "
                "band the error is judged in (default: found in the reference)"},
       {.name = "--plot",
        .value = "DIR",
        .help = "write the compared positions and torques into DIR"}});
  return spec;
}

}  // namespace modelgen::internal
