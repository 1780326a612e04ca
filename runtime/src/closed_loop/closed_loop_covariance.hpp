// The sandwich covariance of IDIM-IV and DIDIM on correlated equation errors (issue 31).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "modelgen/estimation/least_squares.hpp"
#include "runtime/src/closed_loop/closed_loop_equations.hpp"

namespace modelgen::detail {

/// With per record and joint: X the instruments (IV) or the simulated regressor (DIDIM), W the
/// regressor the estimate multiplies (measured for IV, simulated for DIDIM) and the residuals,
/// all unweighted (equations' weights applied here): when the weighted residuals are correlated
/// from row to row, replaces fit.std_dev and fit.information by A^-1 S A^-T (A = X^T W, S by
/// Newey-West) and names it in fit.covariance; else leaves fit as it is.
void closed_loop_sandwich(const std::vector<RecordEquations>& equations,
                          const std::vector<std::vector<Eigen::MatrixXd>>& X,
                          const std::vector<std::vector<Eigen::MatrixXd>>& W,
                          const std::vector<std::vector<Eigen::VectorXd>>& residual,
                          LeastSquaresResult& fit);

}  // namespace modelgen::detail
