// modelid fit's options and methods, declared once: the table the command line is parsed by,
// `modelid fit --help` and the usage come from.

#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/data/data_files.hpp"
#include "runtime/cli/fit/fit_methods.hpp"

namespace modelgen::internal {

namespace {

const std::vector<std::string> kLinear = {"ols", "wls", "pim-wls"};
const std::vector<std::string> kClosedLoop = {"iv", "didim"};

OptionSpec method_option() {
  OptionSpec option{.name = "--method",
                    .type = ValueType::kChoice,
                    .value = "METHOD",
                    .help = "the estimator:",
                    .required = true};
  for (const FitMethod& method : fit_methods()) {
    option.choices.push_back(method.name);
    option.help += "\n" + method.name + ": " + method.label + ", " + method.summary;
  }
  return option;
}

CommandSpec make_fit_spec() {
  CommandSpec spec = modelid_command(
      "fit",
      "base parameters and their standard deviations from measured "
      "trajectories, open or closed loop",
      {
          robot_option(),
          {.name = "--data",
           .value = "FILE",
           .help = "a CSV record (one experiment per file)",
           .repeatable = true,
           .required = true},
          method_option(),
          {.name = "-o",
           .value = "EST.json",
           .help = "write the estimate (read by predict, "
                   "validate, export and modelgen --params)"},
          {.name = "--truth",
           .value = "FILE",
           .help = "true parameters, printed beside the "
                   "estimates with their errors"},
          {.name = "--plot",
           .value = "DIR",
           .help = "write measured and fitted torques as CSV and "
                   "SVG into DIR",
           .methods = {"ols", "wls", "pim-wls", "iv", "didim", "pm", "ml-eiv"}},
          {.name = "--essential",
           .type = ValueType::kFlag,
           .help = "also find the essential parameters (iterative elimination, Gautier & Briot)",
           .methods = kLinear},
          {.name = "--r-sigma",
           .type = ValueType::kPositive,
           .value = "R",
           .help = "the elimination ratio of --essential (largest over smallest %std, above 1)",
           .default_value = "20",
           .needs = "--essential"},
          {.name = "--physical",
           .type = ValueType::kFlag,
           .help = "a physically consistent estimate (pseudo-inertia, log-Cholesky) beside the "
                   "unconstrained one"},
          {.name = "--prior-weight",
           .type = ValueType::kPositive,
           .value = "W",
           .help = "weight of the pull towards the description's a-priori values in the "
                   "directions the data do not determine (default: the largest of 1, 0.1, ..., "
                   "1e-4 that raises the rms weighted residual by at most 2 % beyond consistency "
                   "alone; 1e-6 with --method ml)",
           .default_value = "auto",
           .needs = "--physical"},
          {.name = "--min-speed",
           .value = "V[,V2,...]",
           .help = "weight out samples where a joint is slower than V, with a ramp of two filter "
                   "periods before the decimation (one speed or one per joint; default: per joint "
                   "the speed below which the filtered velocity's sign is unreliable, chosen from "
                   "the data; 0: no weighting)",
           .unit = "rad/s or m/s",
           .methods = {"ols", "wls", "pim-wls", "iv", "didim", "pm"}},
          {.name = "--controller",
           .value = "C.yaml",
           .help = "the joint controller the record was made under",
           .methods = kClosedLoop},
          {.name = "--fir-lags",
           .type = ValueType::kWhole,
           .value = "M",
           .help = "lags of the sensitivity FIR on each side",
           .methods = {"pm"}},
          {.name = "--approach",
           .type = ValueType::kChoice,
           .help = "Swevers section 4: 1 linear, 2 nonlinear with R_z = 1, 3 nonlinear with R_z "
                   "unknown, all three side by side",
           .choices = {"1", "2", "3", "all"},
           .methods = {"ml"}},
          {.name = "--unknown",
           .value = "LIST",
           .help = "the unknowns among load, Rv, Rc, Rz (comma-separated)",
           .default_value = "load,Rv,Rc,Rz",
           .methods = {"ml"}},
          {.name = "--known",
           .value = "KNOWN.json",
           .help = "a-priori drive-model values by name ({\"JM3\": 8, ...})",
           .methods = {"ml"}},
      });
  spec.selector = "--method";
  spec.families = {{"the linear methods", kLinear},
                   {"the closed-loop methods", kClosedLoop},
                   {"the projection method", {"pm"}}};
  add_data_options(spec);
  spec.details =
      "C.yaml: {type: pid, sample_time: S, kp: [..], ki: [..], kd: [..]}, one gain per joint; a\n"
      "closed-loop record has columns t, q, tau (the command) and qr (the reference). Data\n"
      "files: CSV with a header t, q1..qn, tau1..taun (or currents i1..in) and optionally\n"
      "dq1.., ddq1.. (docs/file-formats.md).\n";
  return spec;
}

}  // namespace

const CommandSpec& fit_spec() {
  static const CommandSpec spec = make_fit_spec();
  return spec;
}

}  // namespace modelgen::internal
