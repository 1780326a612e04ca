// Maximum-likelihood identification with the nonlinear drive model (Swevers et al. 2002,
// section 3.2 and eq. 18): linear initial guess, rank and condition number of the Jacobian at
// the initial guess, Ceres Levenberg-Marquardt with the analytic Jacobian, standard deviations
// from the Jacobian at the optimum, and the load in physical terms with consistency warnings.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "modelgen/ml/identifiability.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/ml/problem.hpp"

namespace modelgen {

struct MlFitOptions {
  bool linear_initial_guess = true;  ///< section 3.2 (linear_route); else the given values
  int max_iterations = 100;          ///< Levenberg-Marquardt iterations
  double rank_tolerance = 1e-9;      ///< identifiability(): relative singular value
  int threads = 2;                   ///< Ceres evaluation threads
};

struct MlFitResult {
  std::vector<std::string> names;  ///< the unknowns (theta1)
  Eigen::VectorXd initial;         ///< theta1 where the search started (after the linear guess)
  /// Estimates and standard deviations (sqrt of the diagonal of s^2 (J^T J)^-1, J the weighted
  /// Jacobian at the optimum, s^2 = weighted residual sum of squares / (residuals - unknowns));
  /// NaN for every unknown identifiability() marks not identifiable: those are held at their
  /// initial values during the search, and no number is reported for them.
  Eigen::VectorXd value, std_dev;
  Identifiability identifiability;  ///< of the weighted Jacobian at the initial guess
  Eigen::VectorXd all_values;       ///< every ml_param_names() value at the optimum
  /// The load (when load parameters are unknown) with standard deviations (NaN where not
  /// identifiable), and its physical-consistency warnings.
  bool has_load = false;
  LoadParameters load, load_std_dev;
  std::vector<std::string> load_warnings;
  Eigen::VectorXd rms_error;    ///< per motor, N m: rms of measured minus model (0 if not fitted)
  double initial_cost = 0;      ///< 1/2 sum of squared weighted residuals at the start
  double final_cost = 0;        ///< and at the optimum
  double residual_std_dev = 0;  ///< s above
  int iterations = 0;           ///< Levenberg-Marquardt iterations
  double solve_seconds = 0;     ///< Ceres' minimizer time
  bool converged = false;
  std::string solver_report;       ///< Ceres' brief report
  std::vector<std::string> notes;  ///< initial-guess remarks, in words
};

/// Fits `problem`'s unknowns (eq. 18). Throws EstimationError if the search fails numerically
/// (non-finite residuals); a rank-deficient Jacobian is not an error but reported in
/// identifiability and by NaN estimates.
MlFitResult fit_ml(MlProblem& problem, const MlFitOptions& options = {});

}  // namespace modelgen
