// modelid fit: base parameters from measured trajectories by IDIM-OLS, IDIM-WLS or PIM-WLS
// (Gautier & Briot eq. 14-21), from closed-loop records by IDIM-IV, DIDIM or the projection
// method (Bona & Curatella eq. 10-12), or from averaged periods by the errors-in-variables ML
// (eq. 13-16), their standard
// deviations (eq. 17-19), optionally the essential parameters (iterative elimination with
// ratio r_sigma), torque plots and the EST.json file.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/data/trajectory_csv.hpp"
#include "modelgen/estimation/essential.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/estimation/least_squares.hpp"
#include "modelgen/estimation/predict.hpp"
#include "modelgen/io/estimate_file.hpp"
#include "modelgen/io/parameter_file.hpp"
#include "modelgen/model/load_robot.hpp"
#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/model_source.hpp"
#include "runtime/cli/common/progress.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/data/data_files.hpp"
#include "runtime/cli/data/limit_check.hpp"
#include "runtime/cli/fit/closed_loop_fit.hpp"
#include "runtime/cli/fit/eiv_fit.hpp"
#include "runtime/cli/fit/projection_fit.hpp"
#include "runtime/cli/plots/torque_plots.hpp"
#include "runtime/cli/reports/estimate_warnings.hpp"
#include "runtime/cli/reports/physical_report.hpp"
#include "runtime/cli/reports/prediction_output.hpp"
#include "runtime/cli/reports/preparation_check.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

namespace {

// Above this relative standard deviation (%, eq. 19) a parameter is marked as poorly
// identified: a screen marker only, the essential parameter search below is what decides.
constexpr double kPoorlyIdentifiedPercent = 10.0;
// Gautier & Briot, section on essential parameters: r_sigma "ideally chosen between 10 and 30",
// fixed to 20 for all their identifications.
constexpr double kDefaultRSigma = 20.0;
// The prior weight of --physical (modelgen/estimation/physical.hpp): small, it only picks among
// standard sets the data cannot tell apart.
constexpr double kDefaultPriorWeight = 1e-6;
// Above this condition number of the (weighted) W, a fit gets a warning: its estimates move by
// that factor times the relative noise.
constexpr double kIllConditioned = 1e8;

const char* method_name(Method method) {
  switch (method) {
    case Method::kOls:
      return "IDIM-OLS";
    case Method::kWls:
      return "IDIM-WLS";
    case Method::kPimWls:
      return "PIM-WLS";
  }
  return "?";
}

std::vector<EstimatedParameter> estimated(const LeastSquaresResult& fit,
                                          const std::vector<std::string>& names,
                                          const Eigen::VectorXd& truth) {
  std::vector<EstimatedParameter> out;
  for (std::size_t b = 0; b < names.size(); ++b) {
    EstimatedParameter p{names[b], fit.value[b], fit.std_dev[b], fit.rel_std_dev[b], {}};
    if (truth.size()) p.truth = truth[b];
    out.push_back(std::move(p));
  }
  return out;
}

// One row per parameter: value, std, %std, a '*' when %std is above the threshold, and the
// true value when known. Returns whether any row was marked.
bool print_parameter_table(const std::vector<EstimatedParameter>& parameters) {
  const bool with_truth = !parameters.empty() && parameters.front().truth.has_value();
  std::cout << "  parameter          value          std      %std"
            << (with_truth ? "           truth" : "") << "\n";
  bool marked = false;
  for (const EstimatedParameter& p : parameters) {
    const bool poor = !(p.rel_std_dev <= kPoorlyIdentifiedPercent);
    marked = marked || poor;
    // No trailing blanks: the marker column is padded only when a truth column follows.
    const std::string marker = poor ? " *" : (with_truth ? "  " : "");
    std::cout << "  " << pad(p.name, 9) << " " << fixed(p.value, 13, 6) << " "
              << fixed(p.std_dev, 12, 3) << " " << fixed(p.rel_std_dev, 9, 3) << marker
              << (with_truth ? " " + fixed(*p.truth, 13, 6) : "") << "\n";
  }
  return marked;
}

// Names separated by spaces, wrapped before 100 columns under `indent`.
void print_wrapped(const std::vector<std::string>& names, const std::string& indent) {
  std::string line = indent;
  for (const std::string& name : names) {
    if (line.size() > indent.size() && line.size() + 1 + name.size() > 98) {
      std::cout << line << "\n";
      line = indent;
    }
    line += (line.size() > indent.size() ? " " : "") + name;
  }
  if (line.size() > indent.size()) std::cout << line << "\n";
}

// `data`, `decimation`: the experiments as prepared for the fit.
EssentialEstimate essential_estimate(const IdentificationModel& model,
                                     const std::vector<Trajectory>& data,
                                     const std::vector<int>& decimation,
                                     const EssentialParameters& essential, double r_sigma) {
  const std::vector<std::string>& names = model.base_param_names();
  EssentialEstimate out;
  out.r_sigma = r_sigma;
  std::vector<std::string> kept_names;
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(model.num_base_params());
  for (std::size_t k = 0; k < essential.kept.size(); ++k) {
    kept_names.push_back(names[essential.kept[k]]);
    beta[essential.kept[k]] = essential.fit.value[k];
  }
  for (int b : essential.eliminated) out.eliminated.push_back(names[b]);
  out.kept = kept_names;
  out.parameters = estimated(essential.fit, kept_names, Eigen::VectorXd());
  out.condition_number = essential.fit.condition_number;
  // The torque error of the essential model, comparable with the full fit's whatever the
  // method (the PIM fits power equations, not torques).
  std::vector<Trajectory> compared = data;
  out.rel_error_norm = predict_with_progress(model, compared, beta, decimation).rel_error_norm;
  return out;
}

void print_essential(const EssentialEstimate& essential, std::size_t num_base) {
  double largest = 0, smallest = INFINITY;
  for (const EstimatedParameter& p : essential.parameters) {
    largest = std::max(largest, p.rel_std_dev);
    smallest = std::min(smallest, p.rel_std_dev);
  }
  std::cout << "essential parameters (r_sigma " << fixed(essential.r_sigma, 0, 4)
            << "): " << essential.kept.size() << " of " << num_base
            << " kept, largest/smallest %std " << fixed(largest / smallest, 0, 4) << "\n";
  print_parameter_table(essential.parameters);
  if (essential.eliminated.empty()) {
    std::cout << "  eliminated: none\n";
  } else {
    std::cout << "  eliminated, first to last (" << essential.eliminated.size() << "):\n";
    print_wrapped(essential.eliminated, "    ");
  }
  std::cout << "  relative error norm of the torques " << fixed(essential.rel_error_norm, 0, 4)
            << ", condition number " << fixed(essential.condition_number, 0, 4) << "\n";
}

// The description behind --robot: the file, or for a compiled-in model its description in the
// source tree.
const RobotModel& description_of(const ModelSource& source, const std::string& robot) {
  if (const RobotModel* description = source.any_description()) return *description;
  throw std::runtime_error("--physical needs the robot's description (its bodies and a-priori "
                           "values); give --robot the description file instead of '" +
                           robot + "'");
}

// fit's table checked that it is positive and comes with --physical.
double prior_weight(const CommandLine& args) {
  if (!args.has("--prior-weight")) return kDefaultPriorWeight;
  return parse_number(args.one("--prior-weight"), "--prior-weight");
}

std::vector<EstimatedParameter> estimated(const Eigen::VectorXd& value,
                                          const Eigen::VectorXd& std_dev,
                                          const std::vector<std::string>& names,
                                          const Eigen::VectorXd& truth) {
  std::vector<EstimatedParameter> out;
  for (std::size_t b = 0; b < names.size(); ++b) {
    const auto i = static_cast<Eigen::Index>(b);
    const double rel = value[i] != 0 ? 100 * std_dev[i] / std::abs(value[i]) : INFINITY;
    EstimatedParameter p{names[b], value[i], std_dev[i], rel, {}};
    if (truth.size()) p.truth = truth[i];
    out.push_back(std::move(p));
  }
  return out;
}

// --min-speed V or V1,...,Vn: one speed for every joint or one per joint (rad/s, m/s), >= 0.
std::vector<double> min_speed(const CommandLine& args, int dof) {
  if (!args.has("--min-speed")) return {};
  return per_axis_values(args.one("--min-speed"), "--min-speed", dof, "speed", "joint",
                         AxisValue::kNonNegative);
}

}  // namespace

int run_fit(const CommandLine& args) {
  // fit's table (fit_options.cpp) checked the method, which options each method takes, the
  // option values' types and what each option needs.
  const double weight = prior_weight(args);
  const std::string& method_text = args.one("--method");
  if (method_text == "ml") return run_fit_ml(args, weight);
  const ModelSource source = load_model_source(args.one("--robot"), angle_tolerance_option(args));
  const IdentificationModel& model = *source.model;
  const std::optional<ClosedLoopMethod> closed_loop = closed_loop_method(method_text);
  const bool projection = method_text == "pm";
  const bool eiv = is_eiv_method(method_text);
  if (eiv) check_eiv_arguments(args);
  const Method method = closed_loop || projection || eiv ? Method::kWls : parse_method(method_text);
  const std::string label = closed_loop  ? closed_loop_method_name(*closed_loop)
                            : projection ? "PM (projection, IDIM-WLS)"
                            : eiv        ? "ML-EIV"
                                         : method_name(method);
  const bool essential = args.has("--essential");
  double r_sigma = kDefaultRSigma;
  if (args.has("--r-sigma")) {
    r_sigma = parse_number(args.one("--r-sigma"), "--r-sigma");
    if (!(r_sigma > 1)) {
      throw UsageError{"--r-sigma must be greater than 1 (largest over smallest %std), not '" +
                       args.one("--r-sigma") + "'"};
    }
  }
  // A plot folder that cannot be made fails now, before the data are read.
  if (args.has("--plot")) check_plot_folder(args.one("--plot"));
  std::ostringstream data_report;
  const Experiments experiments = read_experiments(
      args.all("--data"), model, preparation_options(args), EffortColumns::kRequired, data_report);
  const std::vector<Trajectory>& data = experiments.data;
  warn_beyond_limits(std::cerr, "fit", source, experiments,
                     args.has("--motor-side") ? Side::kMotor : Side::kJoint);

  IdentifyOptions options;
  options.decimation = experiments.decimation;
  options.min_speed = min_speed(args, model.dof());
  if (essential) options.essential_r_sigma = r_sigma;
  Progress fitting("fitting", 1000);
  options.progress = [&fitting](double fraction) {
    fitting.update(static_cast<long long>(1000 * fraction));
  };
  // The truth is read before the fit, so a wrong file costs no fitting time; a truth made from
  // another description (its hash differs) would compare numbers of different parameters.
  Eigen::VectorXd truth;
  if (args.has("--truth")) {
    check_estimate_model(args.one("--truth"), model, "truth");
    truth = read_base_parameters(args.one("--truth"), model);
  }
  std::ostringstream closed_loop_report;
  const Identification id =
      closed_loop  ? fit_closed_loop(args, model, experiments, options.min_speed, *closed_loop,
                                     closed_loop_report, std::cerr)
      : projection ? fit_projection(args, model, experiments, options.min_speed,
                                    closed_loop_report, std::cerr)
      : eiv        ? fit_eiv(model, experiments, closed_loop_report)
                   : identify(model, data, method, options);
  fitting.finish();

  std::cout << "modelid fit: " << model.name() << ", " << label << " on "
            << data.size() << " experiment(s), " << id.samples << " samples\n"
            << data_report.str() << closed_loop_report.str();
  if (!options.min_speed.empty()) {
    std::cout << "  --min-speed: " << id.slow_samples << " of " << id.samples + id.slow_samples
              << " samples left out (a joint slower than its minimum speed, after the "
                 "decimation)\n";
  }
  const std::vector<EstimatedParameter> parameters = estimated(id.fit, id.names, truth);
  if (print_parameter_table(parameters)) {
    std::cout << "  * %std above " << kPoorlyIdentifiedPercent
              << ": poorly identified by these data\n";
  }
  std::cout << "  relative error norm of the torques " << fixed(id.torque_rel_error_norm, 0, 4)
            << ", condition number " << fixed(id.fit.condition_number, 0, 4) << "\n";
  // A fit can be full rank and still useless: say so rather than exit quietly.
  if (id.fit.condition_number > kIllConditioned || !(id.torque_rel_error_norm < 1)) {
    std::cerr << "modelid: warning: this fit explains the torques poorly (relative error norm "
              << fixed(id.torque_rel_error_norm, 0, 3) << ", condition number "
              << fixed(id.fit.condition_number, 0, 3)
              << "): the data excite some parameters too little; more or richer experiments "
                 "help (the PIM needs a block-triangular set, Gautier & Briot section IV)\n";
  }
  warn_residual_outside_band(std::cerr, model, experiments, id.fit.value);
  // Negative friction or rotor inertia, non-positive masses among the unregrouped parameters.
  warn_implausible_estimates(std::cerr, id.names, id.fit.value, id.fit.std_dev);
  std::cout << "  rms torque error per axis (rms torque):";
  for (Eigen::Index j = 0; j < id.rms_error.size(); ++j) {
    std::cout << " " << fixed(id.rms_error[j], 0, 3) << " (" << fixed(id.rms_torque[j], 0, 3)
              << ")";
  }
  std::cout << "\n";

  std::optional<PhysicalEstimate> physical;
  TorquePrediction physical_prediction;
  if (args.has("--physical")) {
    physical = physical_estimate(description_of(source, args.one("--robot")), model, id.fit, weight);
    std::vector<Trajectory> compared = data;
    physical_prediction =
        predict_with_progress(model, compared, physical->fit.base, experiments.decimation);
    physical->rel_error_norm = physical_prediction.rel_error_norm;
    print_physical(std::cout, id.names, id.fit, id.torque_rel_error_norm, *physical,
                   id.fit.equations - static_cast<long long>(id.names.size()));
  }

  EstimateFile estimate;
  if (essential) {
    estimate.essential =
        essential_estimate(model, data, experiments.decimation, id.essential, r_sigma);
    print_essential(*estimate.essential, id.names.size());
  }
  if (args.has("--plot")) {
    // Torques compared where the fit compared them: after the parallel decimation's filter.
    std::vector<Trajectory> compared = data;
    const TorquePrediction prediction =
        predict_with_progress(model, compared, id.fit.value, experiments.decimation);
    write_torque_plots(args.one("--plot"), model.name() + " " + label + " fit",
                       compared, prediction, std::cout, std::cerr);
  }
  if (args.has("-o")) {
    estimate.model = model.name();
    estimate.description_sha256 = model.description_sha256();
    estimate.method = label;
    estimate.parameters = parameters;
    estimate.rel_error_norm = id.torque_rel_error_norm;
    estimate.condition_number = id.fit.condition_number;
    estimate.residual_std = id.fit.residual_std_dev;
    estimate.rms_per_axis.assign(id.rms_error.data(), id.rms_error.data() + id.rms_error.size());
    estimate.rms_torque_per_axis.assign(id.rms_torque.data(),
                                        id.rms_torque.data() + id.rms_torque.size());
    estimate.samples = id.samples;
    estimate.data = args.all("--data");
    estimate.data_options = data_option_words(args);
    if (physical) {
      // The consistent estimate is the estimate; the unconstrained one stays beside it.
      estimate.physical = physical_block(*physical, parameters, id.torque_rel_error_norm);
      estimate.method += " (physically consistent)";
      estimate.parameters =
          estimated(physical->fit.base, physical->fit.base_std_dev, id.names, truth);
      estimate.rel_error_norm = physical->rel_error_norm;
      const TorquePrediction& p = physical_prediction;
      estimate.rms_per_axis.assign(p.rms_error.data(), p.rms_error.data() + p.rms_error.size());
    }
    write_file(args.one("-o"), estimate_json(estimate));
  }
  return 0;
}

}  // namespace modelgen::internal
