// Essential parameters (Pham & Gautier, as used by Gautier & Briot): the parameters left after
// iteratively eliminating the least certain one, until the relative standard deviations are
// within a ratio r_sigma of each other.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/estimation/accumulator.hpp"
#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/least_squares.hpp"

namespace modelgen {

struct EssentialParameters {
  std::vector<int> kept;        ///< column indices of the essential parameters, ascending
  std::vector<int> eliminated;  ///< in elimination order
  LeastSquaresResult fit;       ///< the estimate on the kept columns
};

/// Essential parameters (Pham & Gautier, as used by Gautier & Briot): starting from all
/// columns, repeatedly drop the one with the largest relative standard deviation until the
/// ratio of the largest to the smallest relative standard deviation is at most `r_sigma`
/// (exact data, every %std 0, keep every parameter). Fits with WLS when `group` is non-empty,
/// else OLS. One pass over W, then every elimination step refits from the factors only.
/// Throws EstimationError as fit_ols/fit_wls do, and for r_sigma not finite or not above 1.
EssentialParameters essential_parameters(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                                         const std::vector<int>& group,
                                         const std::vector<std::string>& names,
                                         double r_sigma = 20.0);

/// Essential parameters of streamed equations: WLS over the accumulator's groups when
/// `weighted`, else OLS. `names`: equations.params() entries.
EssentialParameters essential_parameters(const LeastSquaresAccumulator& equations, bool weighted,
                                         const std::vector<std::string>& names,
                                         double r_sigma = 20.0);

}  // namespace modelgen
