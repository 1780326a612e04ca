// modelid fit: base parameters from measured trajectories by the method of --method (the table
// of fit_methods.cpp: IDIM-OLS, IDIM-WLS, PIM-WLS, IDIM-IV, DIDIM, the projection method,
// ML-EIV; the ML route has its own command flow), with their standard deviations (Gautier &
// Briot eq. 17-19), optionally physically consistent, the essential parameters (iterative
// elimination with ratio r_sigma), torque plots and the EST.json file. run_fit reads as its
// steps: the request, the data, the estimate, the report, the outputs.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

#include "modelgen/estimation/predict.hpp"
#include "modelgen/io/estimate_file.hpp"
#include "modelgen/io/json_file.hpp"
#include "modelgen/io/parameter_file.hpp"
#include "modelgen/ml/physical_fit.hpp"
#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/model_source.hpp"
#include "runtime/cli/common/progress.hpp"
#include "runtime/cli/data/data_files.hpp"
#include "runtime/cli/data/limit_check.hpp"
#include "runtime/cli/fit/fit_methods.hpp"
#include "runtime/cli/fit/fit_report.hpp"
#include "runtime/cli/plots/torque_plots.hpp"
#include "runtime/cli/reports/link_table.hpp"
#include "runtime/cli/reports/method_agreement.hpp"
#include "runtime/cli/reports/physical_report.hpp"
#include "runtime/cli/reports/prediction_output.hpp"
#include "runtime/cli/reports/residual_check.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

namespace {

// Gautier & Briot, section on essential parameters: r_sigma "ideally chosen between 10 and 30",
// fixed to 20 for all their identifications.
constexpr double kDefaultRSigma = 20.0;

// The description behind --robot: the file, or for a compiled-in model its description in the
// source tree.
const RobotModel& description_of(const ModelSource& source, const std::string& robot) {
  if (const RobotModel* description = source.any_description()) return *description;
  throw std::runtime_error(
      "--physical needs the robot's description (its bodies and a-priori "
      "values); give --robot the description file instead of '" +
      robot + "'");
}

// fit's table checked that it is positive and comes with --physical. Unset: the default rule
// of modelgen/estimation/physical.hpp (for --method ml, MlPhysicalOptions' default).
std::optional<double> prior_weight(const CommandLine& args) {
  if (!args.has("--prior-weight")) return std::nullopt;
  return parse_number(args.one("--prior-weight"), "--prior-weight");
}

// --r-sigma R of --essential (the table checked that it is a number given with --essential).
double essential_ratio(const CommandLine& args) {
  if (!args.has("--r-sigma")) return kDefaultRSigma;
  const double r_sigma = parse_number(args.one("--r-sigma"), "--r-sigma");
  if (!(r_sigma > 1)) {
    throw UsageError{"--r-sigma must be greater than 1 (largest over smallest %std), not '" +
                     args.one("--r-sigma") + "'"};
  }
  return r_sigma;
}

// `method`'s estimate; an EstimationError names the data files it comes from (a rank-deficient
// W says which columns, and the files say where to look).
Identification estimate_from_files(const FitMethod& method, const FitContext& context,
                                   const std::vector<std::string>& files) {
  try {
    return method.estimate(context);
  } catch (const EstimationError& e) {
    std::string names;
    for (const std::string& file : files) names += (names.empty() ? "" : ", ") + file;
    throw EstimationError(names + ": " + e.what());
  }
}

// The truth of --truth in base parameters, read before the fit so that a wrong file costs no
// fitting time; a truth made from another description (its hash differs) would compare
// numbers of different parameters. Empty without --truth.
Eigen::VectorXd read_truth(const CommandLine& args, const IdentificationModel& model) {
  if (!args.has("--truth")) return {};
  const JsonDocument truth = read_json_document(args.one("--truth"));  // read once
  check_estimate_model(truth, model, "truth");
  return read_base_parameters(truth, model);
}

// The estimate as EST.json holds it: the consistent one with --physical (the unconstrained one
// beside it), the fit's statistics and the data options predict prepares data with.
EstimateFile estimate_file(const CommandLine& args, const IdentificationModel& model,
                           const std::string& label, const Identification& id,
                           const std::vector<EstimatedParameter>& parameters,
                           const Eigen::VectorXd& truth,
                           const std::optional<PhysicalEstimate>& physical,
                           const TorquePrediction& physical_prediction, double unconstrained_norm) {
  EstimateFile estimate;
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
    estimate.physical = physical_block(*physical, parameters, unconstrained_norm);
    estimate.method += " (physically consistent)";
    estimate.parameters =
        estimated(physical->fit.base, physical->fit.base_std_dev, id.names, truth);
    estimate.rel_error_norm = physical->rel_error_norm;
    const TorquePrediction& p = physical_prediction;
    estimate.rms_per_axis.assign(p.rms_error.data(), p.rms_error.data() + p.rms_error.size());
  }
  return estimate;
}

// A closed-loop estimate beside IDIM-WLS on the same prepared rows (issue 31): one linear fit
// more, whose changes beyond the standard deviations are warned about. The IDIM-WLS estimate,
// none for the other methods (or when it cannot be made).
std::optional<Identification> compare_with_wls(const FitMethod& method, const FitContext& context,
                                               const Identification& id) {
  if (method.name != "iv" && method.name != "didim") return std::nullopt;
  IdentifyOptions plain = context.options;
  plain.progress = nullptr;
  plain.essential_r_sigma.reset();
  try {
    Identification wls = identify(context.model, context.experiments.data, Method::kWls, plain);
    warn_method_changes(context.log, method.label, id, wls);
    return wls;
  } catch (const EstimationError&) {
    return std::nullopt;  // the closed-loop fit started from this one: rarely reached
  }
}

// Does the model explain each joint's torque in the band down to the record's noise? Judged
// with the estimate whose equation error is least (IDIM-WLS beside a closed-loop method,
// whose estimate minimises another criterion and differs by its own check): the question is
// the model's, the methods' differences are warn_method_changes'.
void check_residual(const FitContext& context, const Identification& id,
                    const std::optional<Identification>& wls) {
  warn_residual_against_noise(context.log, context.model, context.experiments,
                              wls ? wls->fit.value : id.fit.value,
                              wls ? " (of the IDIM-WLS estimate)" : "");
}

// Whether --method takes --min-speed (fit's option table).
bool takes_min_speed(const std::string& method) {
  for (const OptionSpec& option : fit_spec().options) {
    if (option.name == "--min-speed") {
      return std::find(option.methods.begin(), option.methods.end(), method) !=
             option.methods.end();
    }
  }
  return false;
}

// Without --min-speed: per joint the largest of the experiments' reversal_min_speed (the
// speed below which any record's prepared velocity has an unreliable sign); none when every
// one is 0 (clean reversals: nothing is weighted) or no experiment was filtered.
std::vector<double> data_min_speed(const Experiments& experiments, int dof) {
  std::vector<double> speed(static_cast<std::size_t>(dof), 0.0);
  bool any = false;
  for (const Eigen::VectorXd& v : experiments.reversal_speed) {
    for (Eigen::Index j = 0; j < v.size() && j < dof; ++j) {
      speed[static_cast<std::size_t>(j)] = std::max(speed[static_cast<std::size_t>(j)], v[j]);
      any = any || v[j] > 0;
    }
  }
  if (!any) return {};
  // A speed near the joint's own rms speed would weight out most of the record (the filter's
  // velocity noise-dominated): no weighting then, said out loud, rather than a fit on scraps.
  for (int j = 0; j < dof; ++j) {
    double squares = 0;
    Eigen::Index samples = 0;
    for (const Trajectory& x : experiments.data) {
      if (x.dq.cols() != dof) continue;
      squares += x.dq.col(j).squaredNorm();
      samples += x.dq.rows();
    }
    const double rms = samples > 0 ? std::sqrt(squares / static_cast<double>(samples)) : 0.0;
    if (speed[static_cast<std::size_t>(j)] > 0.5 * rms) {
      std::cerr << "modelid fit: warning: joint " << j + 1 << "'s filtered velocity has an "
                << "unreliable sign below " << speed[static_cast<std::size_t>(j)]
                << " rad/s, more than half its rms speed " << rms
                << ": no reversal weighting (lower --cutoff, or give --min-speed)\n";
      return {};
    }
  }
  return speed;
}

std::string chosen_speed_line(const std::vector<double>& speed) {
  std::string line = "  minimum speed chosen from the data:";
  for (const double v : speed) {
    char value[32];
    std::snprintf(value, sizeof value, " %.3g", v);
    line += value;
  }
  return line +
         " rad/s (or m/s; the speed below which the filtered velocity's sign is "
         "unreliable); --min-speed 0 turns it off\n";
}

// With equations weighed down near reversals (--min-speed, given or chosen) the fit's relative
// error norm covers only what it weighs; the consistent estimate, predict and other fits are
// compared over every sample, so that figure is the unconstrained fit's to stand beside them.
std::optional<double> every_sample_rel_error_norm(const IdentificationModel& model,
                                                  const Experiments& experiments,
                                                  const std::vector<double>& min_speed,
                                                  const Eigen::VectorXd& value) {
  if (std::none_of(min_speed.begin(), min_speed.end(), [](double v) { return v > 0; })) {
    return std::nullopt;
  }
  std::vector<Trajectory> compared = experiments.data;
  return predict_with_progress(model, compared, value, experiments.decimation).rel_error_norm;
}

}  // namespace

int run_fit(const CommandLine& args) {
  // The request: fit's table (fit_options.cpp) checked the method, which options each method
  // takes, the values' types and what each option needs; the method checks the rest.
  const FitMethod& method = fit_method(args.one("--method"));
  const std::optional<double> weight = prior_weight(args);
  if (method.route == FitRoute::kDriveModel) {
    return run_fit_ml(args, weight.value_or(MlPhysicalOptions{}.prior_weight));
  }
  if (method.check != nullptr) method.check(args);
  const double r_sigma = essential_ratio(args);
  const ModelSource source = load_model_source(args.one("--robot"), args);
  const IdentificationModel& model = *source.model;
  // A plot folder that cannot be made fails now, before the data are read.
  if (args.has("--plot")) check_plot_folder(args.one("--plot"));

  // The data, each file read once.
  std::ostringstream data_report;
  const Experiments experiments =
      read_experiments(args.all("--data"), model, preparation_options(args),
                       EffortColumns::kRequired, data_report, method.keeps_records);
  warn_beyond_limits(std::cerr, "fit", source, experiments,
                     args.has("--motor-side") ? Side::kMotor : Side::kJoint);
  const Eigen::VectorXd truth = read_truth(args, model);

  // The estimate.
  IdentifyOptions options;
  options.decimation = experiments.decimation;
  options.reversal_guard = experiments.reversal_guard;
  // A periodic experiment whose torques keep harmonics 0..H: its equation errors live on
  // those lines (identify() then uses a sandwich covariance, issue 31).
  for (std::size_t e = 0; e < experiments.noise.size(); ++e) {
    const PeriodicNoise& noise = experiments.noise[e];
    const bool cut = !noise.empty() && noise.tau_lines.rows() > 0 &&
                     noise.samples == experiments.data[e].t.size();
    options.torque_harmonics.push_back(cut ? static_cast<int>(noise.tau_lines.rows()) - 1 : -1);
  }
  std::string chosen_speed;
  if (args.has("--min-speed")) {
    options.min_speed = per_axis_values(args.one("--min-speed"), "--min-speed", model.dof(),
                                        "speed", "joint", AxisValue::kNonNegative);
  } else if (takes_min_speed(method.name)) {
    options.min_speed = data_min_speed(experiments, model.dof());
    if (!options.min_speed.empty()) chosen_speed = chosen_speed_line(options.min_speed);
  }
  if (args.has("--essential")) options.essential_r_sigma = r_sigma;
  Progress fitting("fitting", 1000);
  options.progress = [&fitting](double fraction) {
    fitting.update(static_cast<long long>(1000 * fraction));
  };
  std::ostringstream method_report;
  const FitContext context{args, model, experiments, options, method_report, std::cerr};
  const Identification id = estimate_from_files(method, context, args.all("--data"));
  fitting.finish();

  // The report.
  const std::vector<EstimatedParameter> parameters = estimated(id.fit, id.names, truth);
  const std::optional<double> every_sample_norm =
      every_sample_rel_error_norm(model, experiments, options.min_speed, id.fit.value);
  const double comparable_norm = every_sample_norm.value_or(id.torque_rel_error_norm);
  print_fit({model, method.label, experiments, id, data_report.str(), method_report.str(),
             args.has("--min-speed") || !chosen_speed.empty(), chosen_speed, every_sample_norm},
            parameters);
  check_residual(context, id, compare_with_wls(method, context, id));
  std::optional<PhysicalEstimate> physical;
  TorquePrediction physical_prediction;
  if (args.has("--physical")) {
    physical =
        physical_estimate(description_of(source, args.one("--robot")), model, id.fit, weight);
    std::vector<Trajectory> compared = experiments.data;
    physical_prediction =
        predict_with_progress(model, compared, physical->fit.base, experiments.decimation);
    physical->rel_error_norm = physical_prediction.rel_error_norm;
    print_physical(std::cout, id.names, id.fit, comparable_norm, *physical,
                   id.fit.equations - static_cast<long long>(id.names.size()));
    warn_far_links(std::cerr, physical->links);
    warn_unconverged(std::cerr, *physical);
  }
  std::optional<EssentialEstimate> essential;
  if (args.has("--essential")) {
    essential =
        essential_estimate(model, experiments.data, experiments.decimation, id.essential, r_sigma);
    print_essential(*essential, id.names.size());
  }

  // The outputs.
  if (args.has("--plot")) {
    // Torques compared where the fit compared them: after the parallel decimation's filter.
    std::vector<Trajectory> compared = experiments.data;
    const TorquePrediction prediction =
        predict_with_progress(model, compared, id.fit.value, experiments.decimation);
    write_torque_plots(args.one("--plot"), model.name() + " " + method.label + " fit", compared,
                       prediction, std::cout, std::cerr);
  }
  if (args.has("-o")) {
    EstimateFile estimate = estimate_file(args, model, method.label, id, parameters, truth,
                                          physical, physical_prediction, comparable_norm);
    estimate.essential = essential;
    write_file(args.one("-o"), estimate_json(estimate));
  }
  return 0;
}

}  // namespace modelgen::internal
