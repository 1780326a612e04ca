// modelid design's options, declared once (modelgen/model/option_table.hpp).

#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/q_limit_option.hpp"

namespace modelgen::internal {

namespace {

CommandSpec make_design_spec() {
  CommandSpec spec = modelid_command(
      "design",
      "an optimal Fourier excitation within the joint limits (NLopt "
      "SLSQP, multi-start)",
      {
          robot_option(),
          {.name = "--period",
           .type = ValueType::kPositive,
           .value = "T",
           .help = "the excitation period (from 0.1 to 1e4)",
           .unit = "s",
           .required = true},
          {.name = "--harmonics",
           .type = ValueType::kCount,
           .value = "N",
           .help = "harmonics per joint (from 1 to 50)",
           .required = true},
          {.name = "-o", .value = "TRAJ.yaml", .help = "the designed trajectory", .required = true},
          {.name = "--axes",
           .value = "1,2,...",
           .help = "the axes that move",
           .default_value = "all"},
          {.name = "--hold",
           .value = "q1=V,...",
           .help = "positions of the axes that do not move",
           .unit = "rad or m",
           .default_value = "0 or the middle of their range"},
          {.name = "--criterion",
           .type = ValueType::kChoice,
           .help = "cond: log of the condition number of the base regressor; logdet: minus the log "
                   "determinant of its information matrix",
           .default_value = "cond",
           .choices = {"cond", "logdet"}},
          {.name = "--margin",
           .type = ValueType::kPositive,
           .value = "F",
           .help = "the fraction of every limit the design may use (in (0, 1])",
           .default_value = "0.95"},
          {.name = "--starts",
           .type = ValueType::kCount,
           .value = "K",
           .help = "optimisations from the best random feasible starts (from 1 to 100)",
           .default_value = "3"},
          {.name = "--seed",
           .type = ValueType::kWhole,
           .value = "S",
           .help = "the seed of the random starts",
           .default_value = "1"},
          {.name = "--noise",
           .type = ValueType::kPositive,
           .value = "SIGMA",
           .help = "the torque noise the expected standard deviations are computed for",
           .unit = "N m",
           .default_value = "1"},
          {.name = "--samples",
           .type = ValueType::kCount,
           .value = "S",
           .help = "instants of one period the regressor is stacked over (from 10 to 100000)",
           .default_value = "40 per period of the highest harmonic"},
          {.name = "--ddq-limit",
           .value = "A[,A2,...]",
           .help = "acceleration limits (one or one per joint; they replace the description's)",
           .unit = "rad/s^2 or m/s^2"},
          q_limit_option_spec(),
          {.name = "--max-evaluations",
           .type = ValueType::kCount,
           .value = "N",
           .help = "evaluations per start (from 1 to 1000000)",
           .default_value = "1000"},
          {.name = "--compare",
           .value = "TRAJ.yaml",
           .help = "evaluate the same criterion on another trajectory"},
          {.name = "--plot", .value = "DIR", .help = "draw the design as check-trajectory --plot"},
      });
  return spec;
}

}  // namespace

const CommandSpec& design_spec() {
  static const CommandSpec spec = make_design_spec();
  return spec;
}

}  // namespace modelgen::internal
