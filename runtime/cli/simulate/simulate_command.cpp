// modelid simulate: samples a Fourier excitation (Swevers 2002, eq. 15-17), computes the joint
// torques of given base parameters by the model's inverse dynamics (Gautier & Briot eq. 4-6),
// or the motor torques of the drive model (Swevers eq. 12, drive_simulation.hpp) mapped to the
// joints, adds seeded Gaussian noise per axis, then writes the trajectory CSV. With
// --controller the excitation is the reference of a joint PID that drives the simulated robot
// (modelgen/closed_loop), as a real robot is recorded.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "modelgen/closed_loop/closed_loop_simulation.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/io/estimate_file.hpp"
#include "modelgen/io/experiment/controller_file.hpp"
#include "modelgen/io/experiment/fourier_file.hpp"
#include "modelgen/io/experiment/plausible_magnitude.hpp"
#include "modelgen/io/experiment/trajectory_csv.hpp"
#include "modelgen/io/json_file.hpp"
#include "modelgen/io/parameter_file.hpp"
#include "modelgen/ml/drive_model.hpp"
#include "modelgen/model/number_text.hpp"
#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/signal/gaussian_noise.hpp"
#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/model_source.hpp"
#include "runtime/cli/common/progress.hpp"
#include "runtime/cli/common/q_limit_option.hpp"
#include "runtime/cli/excitation/trajectory_limits.hpp"
#include "runtime/cli/reports/finite_output.hpp"
#include "runtime/cli/simulate/drive_simulation.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

namespace {

// --noise S or S1,...,Sn: one standard deviation for every axis or one per axis (`axes` names
// them in messages: joints or motors).
std::vector<double> parse_noise(const std::string& text, int dof, const std::string& axes,
                                const std::string& option = "--noise",
                                const std::string& what = "standard deviation") {
  return per_axis_values(text, option, dof, what, axes, AxisValue::kNonNegative);
}

// Where the simulated values come from, for a message about them: the file and which of its
// values is largest (largest_parameter).
struct ValueSource {
  std::string file;
  std::string largest;
};

// Every number simulate writes must be finite and one the data reader takes: a parameter of
// 1e308 gives torques beyond the range of a double, which the CSV would hold as inf, and one
// of 1e300 torques of 1e300, which no robot gives; fit would refuse either on reading it.
void check_output_fit_reads(const Trajectory& x, const ValueSource& values) {
  for (const auto& [column, m] :
       {std::pair{"q", &x.q}, {"dq", &x.dq}, {"ddq", &x.ddq}, {"tau", &x.tau}, {"qr", &x.qr}}) {
    const std::string found = first_non_finite(*m, x.t, column);
    if (!found.empty()) {
      throw InputError({values.file},
                       "the simulated " + found + ", beyond the range of a double" +
                           values.largest +
                           "; simulate writes finite numbers only, and wrote nothing");
    }
    const std::optional<PlausibleMagnitude> plausible =
        plausible_magnitude(std::string(column) + "1");
    for (Eigen::Index s = 0; plausible && s < m->rows(); ++s) {
      for (Eigen::Index j = 0; j < m->cols(); ++j) {
        if (std::abs((*m)(s, j)) <= plausible->bound) continue;
        throw InputError({values.file},
                         "the simulated " + std::string(column) + std::to_string(j + 1) + " is " +
                             shortest_text((*m)(s, j)) + " at t = " + shortest_text(x.t[s]) +
                             " s, beyond any robot (|" + plausible->kind + "| up to " +
                             shortest_text(plausible->bound) + " " + plausible->unit + ")" +
                             values.largest +
                             "; simulate writes only what fit reads, and wrote nothing");
      }
    }
  }
}

// Without --params: the base parameters of the description's a-priori values (URDF
// inertials, YAML `known:`), the ones it lacks taken as 0, which is said.
Eigen::VectorXd a_priori_base_parameters(const ModelSource& source,
                                         const IdentificationModel& model) {
  const RobotModel* description = source.any_description();
  const auto known = [](const std::optional<double>& value) { return value.has_value(); };
  if (description != nullptr && description->param_names() != model.standard_param_names()) {
    throw UsageError{"simulate needs --params TRUE.json: the description found for '" +
                     model.name() + "' has other standard parameters than the model"};
  }
  if (description == nullptr ||
      std::none_of(description->known_values.begin(), description->known_values.end(), known)) {
    throw UsageError{
        "simulate needs --params TRUE.json (base or standard parameters) or --drive "
        "THETA.json (drive model parameters); without them it uses the description's "
        "a-priori values (URDF inertials, YAML 'known:'), and this one has none"};
  }
  Eigen::VectorXd standard = Eigen::VectorXd::Zero(model.num_standard_params());
  std::vector<std::string> missing;
  for (std::size_t k = 0; k < description->known_values.size(); ++k) {
    if (description->known_values[k]) {
      standard[static_cast<Eigen::Index>(k)] = *description->known_values[k];
    } else {
      missing.push_back(model.standard_param_names()[k]);
    }
  }
  std::cerr << "modelid simulate: note: no --params: the description's a-priori values";
  if (!missing.empty()) {
    std::cerr << "; " << missing.size() << " of " << standard.size()
              << " standard parameters have none and are 0:";
    for (std::size_t k = 0; k < missing.size() && k < 8; ++k) std::cerr << " " << missing[k];
    if (missing.size() > 8) std::cerr << " ...";
  }
  std::cerr << "\n";
  // The loaders check each inertial for a negative mass or an indefinite tensor, not for the
  // triangle inequalities about the centre of mass: the a-priori set is held to what
  // --params is.
  std::string problems;
  for (const PhysicalViolation& v : physical_violations(description->tree, standard)) {
    problems += (problems.empty() ? "" : "; ") +
                (v.body >= 0 ? "link '" + description->tree.bodies[static_cast<std::size_t>(v.body)].name + "' " : std::string()) +
                v.parameter + ": " + v.condition;
  }
  if (!problems.empty()) {
    throw std::runtime_error(description->source_file +
                             ": error: its a-priori values cannot be those of a physical robot: " +
                             problems + "; give --params instead");
  }
  Eigen::VectorXd beta(model.num_base_params());
  model.base_from_standard(standard.data(), beta.data());
  return beta;
}

// --controller: the robot under its joint controller (modelgen/closed_loop), started on the
// reference's state at t = 0; writes t, q (measured), tau (commanded, plus noise), qr.
Trajectory simulate_under_controller(const CommandLine& args, const IdentificationModel& model,
                                     const std::vector<double>& beta,
                                     const FourierTrajectory& fourier, std::uint64_t seed,
                                     const ValueSource& values) {
  if (args.has("--noise") || args.has("--sample-time")) {
    throw UsageError{"with --controller the torque noise is --noise-tau and the sample time the "
                     "controller's sample_time; --noise and --sample-time are for open loop"};
  }
  const int n = model.dof();
  std::vector<std::string> warnings;
  PidController controller(read_controller(args.one("--controller"), n, &warnings));
  for (const std::string& warning : warnings) std::cerr << warning << "\n";
  const double ts = controller.gains().sample_time;
  const double periods =
      args.has("--periods") ? parse_number(args.one("--periods"), "--periods") : 1.0;
  const double samples = periods * fourier.period / ts;
  if (!(samples >= 3) || samples > static_cast<double>(kMaxDataRows)) {
    throw UsageError{"--periods must give from 3 to " + std::to_string(kMaxDataRows) +
                     " samples at the controller's rate (" + shortest_text(ts) + " s), not " +
                     shortest_text(std::floor(samples)) + " ('" +
                     (args.has("--periods") ? args.one("--periods") : std::string("1")) + "')"};
  }
  auto per_joint = [&](const char* option, const char* what) {
    Eigen::VectorXd values;
    if (args.has(option)) {
      const std::vector<double> v = parse_noise(args.one(option), n, "joint", option, what);
      values = Eigen::Map<const Eigen::VectorXd>(v.data(), n);
    }
    return values;
  };
  ClosedLoopOptions options;
  options.q_noise = per_joint("--noise-q", "standard deviation");
  options.tau_noise = per_joint("--noise-tau", "standard deviation");
  options.encoder_resolution = per_joint("--encoder-resolution", "resolution");
  options.seed = seed;
  if (args.has("--substeps")) {
    const double substeps = parse_number(args.one("--substeps"), "--substeps");
    if (substeps < 1 || substeps > 1000 || substeps != std::floor(substeps)) {
      throw UsageError{"--substeps must be a whole number from 1 to 1000, not '" +
                       args.one("--substeps") + "'"};
    }
    options.substeps = static_cast<int>(substeps);
  }
  // The reference at the controller's samples, from the series itself.
  const Trajectory reference = sample(fourier, ts, periods * fourier.period);
  Progress progress("simulating the closed loop", 1);
  ClosedLoopRun run;
  try {
    run = simulate_closed_loop(model, beta, controller, reference.q, reference.q.row(0).transpose(),
                               reference.dq.row(0).transpose(), options);
  } catch (const std::domain_error& e) {
    throw std::runtime_error(args.one("--controller") + ": error: " + e.what());
  }
  progress.finish();
  Trajectory x;
  x.t = run.t;
  x.q = run.q_measured;
  x.tau = run.tau_recorded;
  x.qr = run.qr;
  x.dq = x.ddq = Eigen::MatrixXd::Zero(x.t.size(), n);
  check_output_fit_reads(x, values);
  const Eigen::VectorXd error = (run.q - run.qr).cwiseAbs().colwise().maxCoeff().transpose();
  std::cerr << "modelid simulate: " << x.t.size() << " samples of " << model.name()
            << " under the PID at " << 1.0 / ts << " Hz written to " << args.one("-o")
            << "; largest tracking error per joint (rad):";
  for (int j = 0; j < n; ++j) std::cerr << " " << error[j];
  std::cerr << "\n";
  return x;
}

}  // namespace

int run_simulate(const CommandLine& args) {
  const bool drive_mode = args.has("--drive");
  ModelSource source = load_model_source(args.one("--robot"), args);
  apply_q_limit_option(args, source);
  if (drive_mode && !source.description) {
    throw UsageError{"--drive needs --robot to be a description file (.yaml/.urdf), not '" +
                     args.one("--robot") + "'"};
  }
  const IdentificationModel& model = *source.model;
  Eigen::VectorXd beta;
  ValueSource values;
  if (!drive_mode && !args.has("--params")) {
    beta = a_priori_base_parameters(source, model);
    values.file = source.any_description()->source_file;
  } else if (!drive_mode) {
    values.file = args.one("--params");
    const JsonDocument parameters = read_json_document(args.one("--params"));  // read once
    check_estimate_model(parameters, model);
    beta = read_base_parameters(parameters, model);
    // A simulation of a robot that cannot exist would make data no robot gives.
    if (const RobotModel* description = source.any_description()) {
      check_physically_possible(parameters, model, *description);
    }
  }
  const FourierTrajectory fourier = read_fourier(args.one("--trajectory"), model.dof());
  // Checked on a dense grid over one period, not at the output samples only: a peak between
  // two samples is still a joint driven into its stop.
  if (!args.has("--ignore-limits")) {
    note_missing_limits(std::cerr, "simulate", source);
    refuse_beyond_limits(args.one("--trajectory"), fourier, source,
                         "modelid simulate: nothing written; modelid check-trajectory shows the use "
                         "of every limit, --ignore-limits simulates it anyway");
  }
  std::uint64_t seed = 1;
  if (args.has("--seed")) {
    const std::string& text = args.one("--seed");
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seed);
    if (ec != std::errc() || end != text.data() + text.size()) {
      throw UsageError{"--seed must be a non-negative integer, not '" + text + "'"};
    }
  }
  if (!drive_mode) values.largest = largest_parameter(beta, model.base_param_names());
  if (args.has("--controller")) {
    const std::vector<double> base(beta.data(), beta.data() + beta.size());
    write_trajectory_csv(args.one("-o"),
                         simulate_under_controller(args, model, base, fourier, seed, values));
    return 0;
  }
  const std::vector<double> noise =
      parse_noise(args.one("--noise"), model.dof(), drive_mode ? "motor" : "joint");
  const double sample_time = args.has("--sample-time")
                                 ? parse_number(args.one("--sample-time"), "--sample-time")
                                 : fourier.period / 1000.0;
  const double periods =
      args.has("--periods") ? parse_number(args.one("--periods"), "--periods") : 1.0;
  const std::string& output = args.one("-o");
  std::optional<ReferenceDriveModel> drive_model;
  DriveTruth truth;
  if (drive_mode) {
    drive_model.emplace(source.description->tree, model.drive_chain());
    truth = read_drive_truth(args.one("--drive"), *source.description, *drive_model);
    values = {args.one("--drive"),
              largest_parameter(truth.theta, drive_model->param_names(), "drive parameter")};
    if (!truth.note.empty()) std::cerr << "modelid simulate: note: " << truth.note << "\n";
  }
  Trajectory x = sample(fourier, sample_time, periods * fourier.period);

  // Noise-free torques: the joint torques of the base parameters (Gautier & Briot eq. 4-6), or
  // the drive model's motor torques (Swevers eq. 12).
  Progress progress("simulating", x.t.size());
  Eigen::MatrixXd tau(x.t.size(), model.dof());
  if (drive_mode) {
    tau = motor_torques(*drive_model, x, truth.theta, progress);
  } else {
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      if (s % 1024 == 0) progress.update(s);
      const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
      Eigen::VectorXd row(model.dof());
      model.inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), row.data());
      tau.row(s) = row.transpose();
    }
  }
  // Gaussian noise per axis by Box-Muller on a fixed generator: the same seed, the same file.
  GaussianNoise gaussian(seed);
  for (Eigen::Index s = 0; s < x.t.size(); ++s) {
    for (int j = 0; j < model.dof(); ++j) {
      x.tau(s, j) = tau(s, j) + noise[static_cast<std::size_t>(j)] * gaussian();
    }
  }
  // Swevers eq. 10 / power balance: the joint torques the motor torques produce,
  // tau = K^T tau_M, which `fit --method ml` maps back by tau_M = K^-T tau (ml_experiment).
  if (drive_mode) x.tau = x.tau * model.drive_chain().motor_from_joint;
  progress.update(x.t.size());
  progress.finish();
  check_output_fit_reads(x, values);
  write_trajectory_csv(output, x);
  std::cerr << "modelid simulate: " << x.t.size() << " samples of " << model.name()
            << " written to " << output << "\n";
  return 0;
}

}  // namespace modelgen::internal
