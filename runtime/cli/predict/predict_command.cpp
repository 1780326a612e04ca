// modelid predict: joint torques of an estimate (base parameters) on measured trajectories by
// the model's inverse dynamics (Gautier & Briot eq. 4-6), compared with the measured torques
// per axis (Swevers 2002, Table 3: rms torque, rms error, error in %) and as a relative error
// norm ||tau - tau_pred|| / ||tau|| (Gautier & Briot, Tables III-IV), in full and in the
// excitation band, next to the record's noise floor there.

#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>

#include "modelgen/io/estimate_file.hpp"
#include "modelgen/io/json_file.hpp"
#include "modelgen/io/parameter_file.hpp"
#include "runtime/cli/common/commands.hpp"
#include "runtime/cli/common/model_source.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/data/data_files.hpp"
#include "runtime/cli/data/limit_check.hpp"
#include "runtime/cli/plots/torque_plots.hpp"
#include "runtime/cli/reports/finite_output.hpp"
#include "runtime/cli/reports/noise_floor_report.hpp"
#include "runtime/cli/reports/prediction_output.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

namespace {

void print_errors(const std::vector<Trajectory>& data, const TorquePrediction& prediction,
                  const BandComparison& band) {
  std::cout << "  axis   rms torque    rms error   error %\n";
  for (Eigen::Index j = 0; j < prediction.rms_torque.size(); ++j) {
    const double torque = prediction.rms_torque[j], error = prediction.rms_error[j];
    // No percentage for an axis that carries no torque in these data.
    const std::string percent = torque > 0 ? fixed(100.0 * error / torque, 9, 4) : "        -";
    std::cout << "  " << fixed(static_cast<double>(j + 1), 4, 3) << " " << fixed(torque, 12, 6)
              << " " << fixed(error, 12, 6) << " " << percent << "\n";
  }
  std::vector<std::string> sources;
  for (const Trajectory& x : data) sources.push_back(x.source);
  print_relative_errors(std::cout, prediction.rel_error_norm, band, sources);
  if (data.size() > 1) {
    for (std::size_t e = 0; e < data.size(); ++e) {
      std::cout << "    experiment " << e + 1 << " (" << data[e].source
                << "): " << fixed(prediction.rel_error_norm_per_experiment[e], 0, 6) << "\n";
    }
  }
}

}  // namespace

int run_predict(const CommandLine& args) {
  const ModelSource source = load_model_source(args.one("--robot"), args);
  const IdentificationModel& model = *source.model;
  const std::string& params = args.one("--params");
  if (!args.has("--data")) throw UsageError{"predict needs at least one --data file"};
  // Before the names are looked up: an estimate of another robot would otherwise fail on a
  // parameter name, or worse, match by chance.
  // Read once: every check and value below comes from this document.
  const JsonDocument estimate = read_json_document(params);
  check_estimate_model(estimate, model);
  const Eigen::VectorXd beta = read_base_parameters(estimate, model);
  // simulate refuses a standard set no body has (a negative mass): its forward dynamics and
  // data would be meaningless. predict evaluates tau = W beta, linear in the base parameters,
  // which physical standard sets may give as well, so its torques are well defined and it
  // says what is wrong but predicts. Base sets are left alone: an unconstrained fit's
  // estimate of a friction may well be negative.
  if (const RobotModel* description = source.any_description()) {
    const PhysicalProblems physical = physical_problems(estimate, model, *description);
    if (physical.key == "standard" && !physical.problems.empty()) {
      std::cerr << physical.where.to_string() << ": warning: " << physical.text()
                << "; predict gives the torques of their base parameters all the same "
                   "(simulate refuses them)\n";
    }
  }
  if (args.has("--plot")) check_plot_folder(args.one("--plot"));
  // The data are prepared as the fit prepared them (EST.json's data options) unless this
  // command line gives data options of its own; stderr says which.
  const std::vector<std::string> given = data_option_words(args);
  const std::optional<std::vector<std::string>> from_estimate = read_data_options(estimate);
  const auto spelled = [](const std::vector<std::string>& words) {
    std::string text;
    for (const std::string& word : words) text += (text.empty() ? "" : " ") + word;
    return text.empty() ? std::string("none") : text;
  };
  PreparationOptions preparation;
  if (!given.empty() || !from_estimate) {
    preparation = preparation_options(args);
    if (from_estimate && *from_estimate != given) {
      std::cerr << "modelid predict: data options from the command line (" << spelled(given)
                << "); the fit's, in " << params << ", were " << spelled(*from_estimate)
                << "\n";
    }
  } else {
    preparation = preparation_options(data_options_from_words(*from_estimate, params));
    std::cerr << "modelid predict: data options from " << params
              << " (as the fit prepared its data): " << spelled(*from_estimate) << "\n";
  }
  // One prediction per input sample unless the fit's decimated comparison is asked for.
  const bool decimated = args.has("--decimated");
  preparation.every_sample = !decimated;
  std::ostringstream data_report;
  Experiments experiments = read_experiments(args.all("--data"), model, preparation,
                                             EffortColumns::kOptional, data_report);
  warn_beyond_limits(std::cerr, "predict", source, experiments, preparation.side);
  // Torques are optional: without them there is nothing to compare, only predictions.
  const bool measured = experiments.data.front().measured != Measured::kNothing;
  for (const Trajectory& x : experiments.data) {
    if ((x.measured != Measured::kNothing) != measured) {
      throw DataError(x.source + ": error: " + (measured ? "no" : "has") +
                      " torque or current columns, unlike " + experiments.data.front().source +
                      ": give them in every file or in none");
    }
  }
  // --decimated: compared where identification compares them, after the parallel
  // decimation's filter (every factor is 1 otherwise).
  const TorquePrediction prediction =
      predict_with_progress(model, experiments.data, beta, experiments.decimation);
  const std::vector<Trajectory>& data = experiments.data;
  check_prediction_finite(params, data, prediction, measured,
                          largest_parameter(beta, model.base_param_names()));

  // The part of the measured torque no model of the excitation explains: above its band, and
  // the noise in it (issue 31). Found before anything is printed: --trajectory may be wrong.
  BandComparison band;
  if (measured) {
    const std::optional<std::string> trajectory =
        args.has("--trajectory") ? std::optional<std::string>(args.one("--trajectory"))
                                 : std::nullopt;
    std::vector<Eigen::MatrixXd> measured_tau;
    for (const Trajectory& x : data) measured_tau.push_back(x.tau);
    band = compare_in_band(data, measured_tau, prediction.error, trajectory, model.dof());
  }
  std::cout << "modelid predict: " << model.name() << " on " << data.size() << " experiment(s), "
            << prediction.samples << " samples, parameters from " << params << "\n"
            << data_report.str();
  if (measured) {
    print_errors(data, prediction, band);
  } else {
    std::cout << "  no measured torques in the data: predicted torques only\n";
  }
  if (args.has("-o")) write_file(args.one("-o"), prediction_csv(data, prediction, true, measured));
  if (args.has("--plot") && !measured) {
    std::cout << "  plots skipped: there are no measured torques to compare with\n";
  } else if (args.has("--plot")) {
    write_torque_plots(args.one("--plot"), model.name() + " predicted with " + params, data,
                       prediction, std::cout, std::cerr);
  }
  return 0;
}

}  // namespace modelgen::internal
