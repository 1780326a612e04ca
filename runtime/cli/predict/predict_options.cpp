// modelid predict's options, declared once (modelgen/model/option_table.hpp).

#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

const CommandSpec& predict_spec() {
  static const CommandSpec spec = [] {
    CommandSpec spec = modelid_command(
        "predict", "torques of an estimate along recorded trajectories, and their errors per axis",
        {robot_option(),
         {.name = "--params",
          .value = "EST.json",
          .help = "an estimate of fit -o, or a {\"base\": ...} or {\"standard\": ...} file",
          .required = true},
         {.name = "--data",
          .value = "FILE",
          .help = "a CSV record (one experiment per file)",
          .repeatable = true,
          .required = true},
         {.name = "-o", .value = "PRED.csv", .help = "write measured and predicted torques"},
         {.name = "--plot", .value = "DIR", .help = "write the torques as CSV and SVG into DIR"},
         {.name = "--trajectory",
          .value = "TRAJ.yaml",
          .help = "the Fourier excitation of the data: its period and top harmonic give the "
                  "band the error is judged in (default: found in the positions)"},
         {.name = "--decimated",
          .type = ValueType::kFlag,
          .help = "compare where the fit compared: after the parallel decimation's filter"}});
    add_data_options(spec);
    spec.details =
        "The data options default to those the fit recorded in EST.json (\"data_options\"), so\n"
        "that predict prepares the data as the fit did.\n";
    return spec;
  }();
  return spec;
}

}  // namespace modelgen::internal
