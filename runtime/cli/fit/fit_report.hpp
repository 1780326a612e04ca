// What modelid fit prints and writes of a base-parameter estimate (fit_report.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/essential.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/estimation/least_squares.hpp"
#include "modelgen/io/estimate_file.hpp"
#include "modelgen/model/identification_model.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

/// The estimates of `fit` by name, with the truth beside them when `truth` has values.
std::vector<io::EstimatedParameter> estimated(const LeastSquaresResult& fit,
                                              const std::vector<std::string>& names,
                                              const Eigen::VectorXd& truth);

/// The same from values and standard deviations (%std computed, +inf for a zero value).
std::vector<io::EstimatedParameter> estimated(const Eigen::VectorXd& value,
                                              const Eigen::VectorXd& std_dev,
                                              const std::vector<std::string>& names,
                                              const Eigen::VectorXd& truth);

/// One row per parameter on standard output: value, std, %std, a '*' above 10 %std, the
/// truth when known. Returns whether a row was marked.
bool print_parameter_table(const std::vector<io::EstimatedParameter>& parameters);

/// The essential parameters of `essential` re-estimated, and the torque error of their model on
/// `data` (prepared as for the fit, with its `decimation`).
io::EssentialEstimate essential_estimate(const IdentificationModel& model,
                                         const std::vector<Trajectory>& data,
                                         const std::vector<int>& decimation,
                                         const EssentialParameters& essential, double r_sigma);

/// The essential parameters on standard output (of `num_base` base parameters).
void print_essential(const io::EssentialEstimate& essential, std::size_t num_base);

/// What print_fit reports on.
struct FitSummary {
  const IdentificationModel& model;
  const std::string& label;  ///< the method's name ("IDIM-WLS")
  const Experiments& experiments;
  const Identification& id;
  std::string data_report;    ///< a line per file (read_experiments)
  std::string method_report;  ///< what the estimator said
  bool min_speed_given = false;  ///< given, or chosen from the data
  std::string min_speed_chosen;  ///< the line saying the speeds chosen from the data, or empty
  /// With equations weighed down near reversals: the relative error norm over every sample.
  std::optional<double> every_sample_rel_error_norm;
};

/// The fit on standard output (heading, parameter table, relative error norm, condition number,
/// rms errors per axis) and its warnings on standard error (poorly explained torques, residual
/// outside the band, implausible estimates).
void print_fit(const FitSummary& fit, const std::vector<io::EstimatedParameter>& parameters);

}  // namespace modelgen::internal
