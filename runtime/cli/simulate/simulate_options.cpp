// modelid simulate's options, declared once (modelgen/model/option_table.hpp).

#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/q_limit_option.hpp"

namespace modelgen::internal {

namespace {

constexpr const char* kClosedLoop = "Closed loop (with --controller)";

CommandSpec make_simulate_spec() {
  CommandSpec spec = modelid_command(
      "simulate",
      "synthetic data from a Fourier excitation: open loop with torque "
      "noise, the drive model, or under a joint controller",
      {
          {.name = "--robot",
           .value = "ROBOT",
           .help = "the description file or shipped model",
           .required = true},
          {.name = "--params",
           .value = "TRUE.json",
           .help = "the true base or standard parameters",
           .default_value = "the description's "
                            "a-priori values"},
          {.name = "--drive",
           .value = "THETA.json",
           .help =
               "simulate the drive model instead: {\"name\": value} over its parameters (XXj..Mj, "
               "JMj, Rvj, Rcj, Rzj, load_m, ...; missing: 0, Rzj 1); the noise goes on the motor "
               "torques"},
          {.name = "--trajectory",
           .value = "TRAJ.yaml",
           .help = "the Fourier excitation (the reference with --controller)",
           .required = true},
          {.name = "--noise",
           .value = "SIGMA[,SIGMA2,...]",
           .help = "torque noise: one standard deviation or one per axis",
           .unit = "N m"},
          {.name = "--seed",
           .type = ValueType::kWhole,
           .value = "N",
           .help = "the random generator's seed",
           .default_value = "1"},
          {.name = "--sample-time",
           .type = ValueType::kPositive,
           .value = "S",
           .help = "the sampling period",
           .unit = "s",
           .default_value = "the period / 1000"},
          {.name = "--periods",
           .type = ValueType::kPositive,
           .value = "K",
           .help = "how many periods to record",
           .default_value = "1"},
          {.name = "--ignore-limits",
           .type = ValueType::kFlag,
           .help = "simulate a trajectory beyond the description's joint limits anyway"},
          q_limit_option_spec(),
          {.name = "-o", .value = "A.csv", .help = "the record to write", .required = true},
          {.name = "--controller",
           .value = "C.yaml",
           .help = "simulate under this joint PID (RK4, smoothed Coulomb friction)",
           .group = kClosedLoop},
          {.name = "--noise-q",
           .value = "S[,S2,...]",
           .help = "position noise the controller sees",
           .unit = "rad",
           .needs = "--controller",
           .group = kClosedLoop},
          {.name = "--noise-tau",
           .value = "S[,S2,...]",
           .help = "noise on the recorded torques",
           .unit = "N m",
           .needs = "--controller",
           .group = kClosedLoop},
          {.name = "--encoder-resolution",
           .value = "R[,R2,...]",
           .help = "position quantisation the controller sees",
           .unit = "rad",
           .needs = "--controller",
           .group = kClosedLoop},
          {.name = "--substeps",
           .type = ValueType::kCount,
           .value = "N",
           .help = "integration steps per controller sample (from 1 to 1000)",
           .default_value = "4",
           .needs = "--controller",
           .group = kClosedLoop},
      });
  spec.exclusive = {
      {"--drive", "--params",
       "simulate either the base parameters (--params) or the drive model (--drive)"},
      {"--controller", "--drive",
       "--controller simulates the joint-side model of --params; the drive model of --drive is "
       "simulated open loop only"},
  };
  spec.details =
      "simulate refuses a trajectory beyond the description's joint limits (checked at 1 kHz or\n"
      "finer over one period) unless --ignore-limits. C.yaml: {type: pid, sample_time: S, kp:\n"
      "[..], ki: [..], kd: [..]}, one gain per joint; the closed-loop record holds t, q "
      "(measured),\n"
      "tau (the command) and qr (the reference).\n";
  return spec;
}

}  // namespace

const CommandSpec& simulate_spec() {
  static const CommandSpec spec = make_simulate_spec();
  return spec;
}

}  // namespace modelgen::internal
