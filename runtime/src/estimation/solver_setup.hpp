// The one Levenberg-Marquardt set-up of the library's Ceres fits (the maximum-likelihood fits of
// ml/fit.cpp and ml/physical_search.cpp, the errors-in-variables fit of errors_in_variables.cpp):
// dense QR, tight tolerances, silent, and a failed solve reported as an EstimationError. It
// lives in estimation/ because ml/ builds on estimation/, never the reverse.
#pragma once

#include <string>

#include <ceres/ceres.h>

namespace modelgen::detail {

/// Runs Ceres' Levenberg-Marquardt on `problem` (at most `max_iterations`, on max(1, threads)
/// threads) and returns its summary. Throws EstimationError "<what>: Levenberg-Marquardt failed:
/// <Ceres' message>" when Ceres reports FAILURE; any other termination is the caller's to judge.
ceres::Solver::Summary solve_levenberg_marquardt(ceres::Problem& problem, int max_iterations,
                                                 int threads, const std::string& what);

}  // namespace modelgen::detail
