// Swevers et al. 2002, section 3.2 and eq. 18: the maximum-likelihood fit on Ceres
// (Levenberg-Marquardt, analytic Jacobians from MlProblem's cost functions), with the rank
// analysis of section 4.2 at the initial guess and standard deviations at the optimum.

#include "modelgen/ml/fit.hpp"

#include <ceres/ceres.h>

#include <cmath>
#include <limits>
#include <utility>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/ml/linear_route.hpp"
#include "runtime/src/estimation/solver_setup.hpp"
#include "runtime/src/ml/problem_impl.hpp"
#include "runtime/src/ml/standard_deviations.hpp"

namespace modelgen {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

MlFitResult fit_ml(MlProblem& problem, const MlFitOptions& options) {
  MlFitResult result;
  result.names = problem.unknown_names();
  const int U = problem.num_unknowns();
  const int P = problem.model().num_params();
  if (options.linear_initial_guess) {
    LinearRoute route = linear_route(problem, options.rank_tolerance);
    problem.set_values(route.values);
    result.notes = std::move(route.fit.notes);
  }
  result.initial = problem.initial();

  // Section 4.2: rank of the Jacobian at the initial guess decides what can be identified.
  Eigen::VectorXd residuals;
  Eigen::MatrixXd J;
  problem.evaluate(result.initial, residuals, &J);
  if (!residuals.allFinite() || !J.allFinite()) {
    throw EstimationError(
        "maximum likelihood: the residuals or their Jacobian are not finite at "
        "the initial guess (check the known values, e.g. an efficiency of 0)");
  }
  result.identifiability = identifiability(J, result.names, options.rank_tolerance);
  result.initial_cost = 0.5 * residuals.squaredNorm();

  Eigen::VectorXd theta1 = result.initial;
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem solver_problem(problem_options);
  for (ceres::CostFunction* cost : detail::MlProblemAccess::cost_functions(problem)) {
    solver_problem.AddResidualBlock(cost, nullptr, theta1.data());
  }
  std::vector<int> held;
  for (int u = 0; u < U; ++u) {
    if (!result.identifiability.identifiable[u]) held.push_back(u);
  }
  if (static_cast<int>(held.size()) == U) {
    solver_problem.SetParameterBlockConstant(theta1.data());
  } else if (!held.empty()) {
    solver_problem.SetManifold(theta1.data(), new ceres::SubsetManifold(U, held));
  }
  const ceres::Solver::Summary summary = detail::solve_levenberg_marquardt(
      solver_problem, options.max_iterations, options.threads, "maximum likelihood");
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.solve_seconds = summary.minimizer_time_in_seconds;
  result.solver_report = summary.BriefReport();

  problem.evaluate(theta1, residuals, &J);
  result.final_cost = 0.5 * residuals.squaredNorm();
  const Eigen::Index dof_free =
      problem.num_residuals() - (U - static_cast<Eigen::Index>(held.size()));
  const double s2 =
      residuals.squaredNorm() / static_cast<double>(std::max<Eigen::Index>(1, dof_free));
  result.residual_std_dev = std::sqrt(s2);
  result.std_dev = detail::standard_deviations(J, result.identifiability.identifiable, s2);
  result.value = theta1;
  for (int u = 0; u < U; ++u) {
    if (!result.identifiability.identifiable[u]) result.value[u] = kNaN;
  }
  result.all_values = problem.with_unknowns(theta1);

  const Eigen::MatrixXd errors = problem.torque_errors(result.all_values);
  result.rms_error =
      (errors.colwise().squaredNorm() / static_cast<double>(errors.rows())).cwiseSqrt().transpose();

  // The load in physical terms: m, c, I_c with standard deviations; NaN where not identifiable.
  Eigen::VectorXd load(kLoadParams), load_sd = Eigen::VectorXd::Constant(kLoadParams, kNaN);
  load = result.all_values.segment(P, kLoadParams);
  for (int u = 0; u < U; ++u) {
    const int k = problem.unknown_indices()[u];
    if (k < P) continue;
    result.has_load = true;
    load_sd[k - P] = result.std_dev[u];
    if (!result.identifiability.identifiable[u]) load[k - P] = kNaN;
  }
  if (result.has_load) {
    result.load = LoadParameters::from_vector(load.data());
    result.load_std_dev = LoadParameters::from_vector(load_sd.data());
    result.load_warnings = load_warnings(result.load);
  }
  return result;
}

}  // namespace modelgen
