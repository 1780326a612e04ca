// The report of fit --method ml-eiv around fit_errors_in_variables.

#include "runtime/cli/fit/eiv_fit.hpp"

#include <cmath>

#include "modelgen/estimation/errors_in_variables.hpp"
#include "runtime/cli/common/text_format.hpp"

namespace modelgen::internal {

void check_eiv_arguments(const CommandLine& args) {
  if (!args.has("--periodic")) {
    throw UsageError{
        "--method ml-eiv needs --periodic: the noise of the positions, velocities and "
        "accelerations it weighs comes from averaging the periods of a periodic excitation"};
  }
  // --decimate, --min-speed, --essential and --controller are refused by fit's table.
}

namespace {

void print_std(std::ostream& out, const char* what, const Eigen::VectorXd& variance) {
  out << "    " << what << ":";
  for (Eigen::Index j = 0; j < variance.size(); ++j) {
    out << " " << fixed(std::sqrt(variance[j]), 0, 3);
  }
  out << "\n";
}

}  // namespace

Identification fit_eiv(const IdentificationModel& model, const Experiments& experiments,
                       std::ostream& report) {
  const std::vector<Trajectory>& data = experiments.data;
  for (std::size_t e = 0; e < data.size(); ++e) {
    if (experiments.noise[e].empty()) {
      throw UsageError{data[e].source + ": --method ml-eiv needs the periodic route (--periodic)"};
    }
  }
  const ErrorsInVariablesResult result =
      fit_errors_in_variables(model, data, experiments.noise);
  for (std::size_t e = 0; e < data.size(); ++e) {
    const PeriodicNoise& v = experiments.noise[e];
    report << "  noise std used per axis, " << data[e].source << ":\n";
    print_std(report, "q (rad)", v.q);
    print_std(report, "dq (rad/s)", v.dq);
    print_std(report, "ddq (rad/s^2)", v.ddq);
    print_std(report, "tau (N m)", v.tau);
  }
  report << "  start: IDIM-WLS, relative error norm "
         << fixed(result.initial.torque_rel_error_norm, 0, 4) << "; eq. 15 cost "
         << fixed(result.initial_cost, 0, 6) << " -> " << fixed(result.final_cost, 0, 6) << " in "
         << result.iterations << " iterations ("
         << (result.converged ? "converged" : "NOT converged") << "), residual std "
         << fixed(result.id.fit.residual_std_dev, 0, 3) << " (1 when the noise model is right)\n"
         << "  Ceres: " << result.solver_report << "\n";
  return result.id;
}

}  // namespace modelgen::internal
