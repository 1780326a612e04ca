// What modelid fit prints and writes of a base-parameter estimate: the parameter table with
// %std (Gautier & Briot eq. 19) and the truth, the essential parameters, the fit's summary.

#include "runtime/cli/fit/fit_report.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>

#include "modelgen/estimation/predict.hpp"
#include "runtime/cli/common/text_format.hpp"
#include "runtime/cli/reports/estimate_warnings.hpp"
#include "runtime/cli/reports/prediction_output.hpp"
#include "runtime/cli/reports/preparation_check.hpp"
#include "runtime/cli/reports/truth_comparison.hpp"

namespace modelgen::internal {

using namespace modelgen::io;  // the file formats (modelgen/io/)

namespace {

// Above this relative standard deviation (%, eq. 19) a parameter is marked as poorly
// identified: a screen marker only, the essential parameter search is what decides.
constexpr double kPoorlyIdentifiedPercent = 10.0;
// Above this condition number of the (weighted) W, a fit gets a warning: its estimates move by
// that factor times the relative noise.
constexpr double kIllConditioned = 1e8;

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

// A right-aligned column of 10 characters: the value, or '-' when there is none.
std::string optional_fixed(const std::optional<double>& value) {
  return value ? fixed(*value, 10, 3) : std::string(9, ' ') + "-";
}

}  // namespace

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

// One row per parameter: value, std, %std, a '*' when %std is above the threshold, and the
// true value when known. Returns whether any row was marked.
bool print_parameter_table(const std::vector<EstimatedParameter>& parameters) {
  const bool with_truth = !parameters.empty() && parameters.front().truth.has_value();
  std::cout << "  parameter          value          std      %std"
            << (with_truth ? "           truth    error %    err/std" : "") << "\n";
  bool marked = false;
  for (const EstimatedParameter& p : parameters) {
    const bool poor = !(p.rel_std_dev <= kPoorlyIdentifiedPercent);
    marked = marked || poor;
    // No trailing blanks: the marker column is padded only when a truth column follows.
    const std::string marker = poor ? " *" : (with_truth ? "  " : "");
    std::cout << "  " << pad(p.name, 9) << " " << fixed(p.value, 13, 6) << " "
              << fixed(p.std_dev, 12, 3) << " " << fixed(p.rel_std_dev, 9, 3) << marker
              << (with_truth
                      ? " " + fixed(*p.truth, 13, 6) + " " + optional_fixed(percent_from_truth(p)) +
                            " " + optional_fixed(sigmas_from_truth(p))
                      : "")
              << "\n";
  }
  return marked;
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

void print_fit(const FitSummary& fit, const std::vector<EstimatedParameter>& parameters) {
  const Identification& id = fit.id;
  std::cout << "modelid fit: " << fit.model.name() << ", " << fit.label << " on "
            << fit.experiments.data.size() << " experiment(s), " << id.samples << " samples\n"
            << fit.data_report << fit.method_report;
  std::cout << fit.min_speed_chosen;
  if (fit.min_speed_given) {
    std::cout << "  --min-speed: " << id.slow_samples << " of " << id.samples + id.slow_samples
              << " samples left out (a joint slower than its minimum speed, after the "
                 "decimation)\n";
  }
  if (print_parameter_table(parameters)) {
    std::cout << "  * %std above " << kPoorlyIdentifiedPercent
              << ": poorly identified by these data\n";
  }
  // Not eq. 18's s^2 (W^T W)^-1: say which covariance the std column is.
  if (!id.fit.covariance.empty()) std::cout << "  std: " << id.fit.covariance << "\n";
  if (!parameters.empty() && parameters.front().truth) {
    print_truth_comparison(compare_with_truth(parameters, kPoorlyIdentifiedPercent),
                           kPoorlyIdentifiedPercent);
  }
  std::cout << "  relative error norm of the torques " << fixed(id.torque_rel_error_norm, 0, 4);
  if (fit.every_sample_rel_error_norm) {
    // The weighted-down reversals are where the friction model is least right: without them
    // the figure flatters the model, so the one predict would give stands beside it.
    std::cout << " over the equations the fit weighs ("
              << fixed(*fit.every_sample_rel_error_norm, 0, 4)
              << " over every sample, reversals included)";
  }
  std::cout << ", condition number " << fixed(id.fit.condition_number, 0, 4) << "\n";
  // A fit can be full rank and still useless: say so rather than exit quietly.
  if (id.fit.condition_number > kIllConditioned || !(id.torque_rel_error_norm < 1)) {
    std::cerr << "modelid: warning: this fit explains the torques poorly (relative error norm "
              << fixed(id.torque_rel_error_norm, 0, 3) << ", condition number "
              << fixed(id.fit.condition_number, 0, 3)
              << "): the data excite some parameters too little; more or richer experiments "
                 "help (the PIM needs a block-triangular set, Gautier & Briot section IV)\n";
  }
  warn_residual_outside_band(std::cerr, fit.model, fit.experiments, id.fit.value);
  // Negative friction or rotor inertia, non-positive masses among the unregrouped parameters.
  warn_implausible_estimates(std::cerr, id.names, id.fit.value, id.fit.std_dev);
  std::cout << "  rms torque error per axis (rms torque):";
  for (Eigen::Index j = 0; j < id.rms_error.size(); ++j) {
    std::cout << " " << fixed(id.rms_error[j], 0, 3) << " (" << fixed(id.rms_torque[j], 0, 3)
              << ")";
  }
  std::cout << "\n";
}

}  // namespace modelgen::internal
