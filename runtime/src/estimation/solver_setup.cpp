// The shared Levenberg-Marquardt set-up of solver_setup.hpp.

#include "runtime/src/estimation/solver_setup.hpp"

#include <algorithm>

#include "modelgen/estimation/estimation_error.hpp"

namespace modelgen::detail {

ceres::Solver::Summary solve_levenberg_marquardt(ceres::Problem& problem, int max_iterations,
                                                 int threads, const std::string& what) {
  ceres::Solver::Options solver_options;
  solver_options.minimizer_type = ceres::TRUST_REGION;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = max_iterations;
  solver_options.num_threads = std::max(1, threads);
  solver_options.function_tolerance = 1e-12;
  solver_options.parameter_tolerance = 1e-12;
  solver_options.gradient_tolerance = 1e-14;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);
  if (summary.termination_type == ceres::FAILURE) {
    throw EstimationError(what + ": Levenberg-Marquardt failed: " + summary.message);
  }
  return summary;
}

}  // namespace modelgen::detail
