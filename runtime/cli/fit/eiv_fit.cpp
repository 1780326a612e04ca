// The report of fit --method ml-eiv around fit_errors_in_variables.

#include "runtime/cli/fit/eiv_fit.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

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

void print_coupling(std::ostream& out, const std::string& source, const NoiseCoupling& coupling) {
  if (coupling.empty()) return;
  // "-": no band with noise on both sides (exact positions), nothing to test.
  auto value = [&](const Eigen::VectorXd& v, Eigen::Index j) {
    return coupling.bands[j] == 0 ? std::string("-") : fixed(v[j], 0, 3);
  };
  out << "  q-tau error coupling per axis, " << source << " (" << coupling.degrees
      << " degrees per band of " << coupling.lines_per_band << " lines):\n    correlation:";
  for (Eigen::Index j = 0; j < coupling.z.size(); ++j) out << " " << value(coupling.correlation, j);
  out << "\n    independence z:";
  for (Eigen::Index j = 0; j < coupling.z.size(); ++j) out << " " << value(coupling.z, j);
  out << "\n";
}

}  // namespace

// Measured on the COMAU scenario (docs/real-data.md, modelid_comau_scenario_test): the
// period-to-period spread of q is 5-7e-8 rad against the 1.4e-7 rad rms of the encoder's
// quantisation (most of it repeats with the loop's motion), and the spread of tau correlates
// 0.34-0.62 with the PD response to the spread of q on joints 1-3.
std::string closed_loop_refusal(const std::string& source) {
  return source +
         ": error: --method ml-eiv refuses a closed-loop record (it carries the reference columns "
         "qr1..qrn): eq. 16 takes the noise of q and tau as independent and measures it by the "
         "spread of the periods, but under a controller the encoder's error repeats from period "
         "to period with the motion (the spread misses most of it, and its acceleration biases "
         "the inertias) and the controller feeds it into the torque (the errors of q and tau are "
         "correlated); on the simulated COMAU closed loop 36 of 64 base parameters end beyond "
         "3 standard deviations, residual std 2.9. Use --method iv or didim with --controller "
         "(the non-periodic route), or wls";
}

std::string coupling_refusal(const std::string& source, const NoiseCoupling& coupling) {
  std::string joints, correlations, scores;
  for (Eigen::Index j = 0; j < coupling.z.size(); ++j) {
    if (!noise_coupled(coupling, j)) continue;
    const std::string separator = joints.empty() ? "" : ", ";
    joints += separator + std::to_string(j + 1);
    correlations += separator + fixed(coupling.correlation[j], 0, 2);
    scores += separator + fixed(coupling.z[j], 0, 3);
  }
  return source +
         ": error: --method ml-eiv refuses this record: the torque's deviations from period to "
         "period follow the position's on joint(s) " +
         joints + " (correlation " + correlations + "; independence test z = " + scores +
         ", refused beyond " + fixed(kCouplingZ, 0, 0) + " with a correlation of at least " +
         fixed(kCouplingCorrelation, 0, 2) +
         "), as under a controller that feeds the encoder's error into the torque command; "
         "eq. 16 takes the errors of q and tau as independent, so its estimate would be biased "
         "and its standard deviations too small. Use --method iv or didim with --controller "
         "(the non-periodic route), or wls";
}

Identification fit_eiv(const IdentificationModel& model, const Experiments& experiments,
                       std::ostream& report, std::ostream& log) {
  const std::vector<Trajectory>& data = experiments.data;
  for (std::size_t e = 0; e < data.size(); ++e) {
    if (experiments.noise[e].empty()) {
      throw UsageError{data[e].source + ": --method ml-eiv needs the periodic route (--periodic)"};
    }
  }
  for (const Trajectory& raw : experiments.raw) {
    if (raw.qr.size() != 0) throw std::runtime_error(closed_loop_refusal(raw.source));
  }
  for (std::size_t e = 0; e < data.size(); ++e) {
    const NoiseCoupling& coupling = experiments.noise[e].coupling;
    print_coupling(report, data[e].source, coupling);
    for (Eigen::Index j = 0; j < coupling.z.size(); ++j) {
      if (noise_coupled(coupling, j)) {
        print_coupling(log, data[e].source, coupling);  // every axis, before the refusal
        throw std::runtime_error(coupling_refusal(data[e].source, coupling));
      }
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
  const double s = result.id.fit.residual_std_dev;
  if (s > kEivResidualStdLimit) {
    log << "modelid: warning: ML-EIV's residual standard deviation is " << fixed(s, 0, 2)
        << " (1 when eq. 16's noise model is right): the averaged period carries errors the "
           "spread of the periods does not show, and the standard deviations are too small by "
           "about that factor; a closed loop does this (the encoder's error repeats with the "
           "motion and the controller feeds it into the torque): use --method iv or didim "
           "with --controller on such a record\n";
  }
  return result.id;
}

}  // namespace modelgen::internal
