// Linear least-squares identification with the statistics of Gautier & Briot (eq. 15-20):
// ordinary and weighted least squares on a stacked observation matrix, standard deviations and
// relative standard deviations of the estimates. Works on any W (IDIM regressor rows, PIM power
// rows, several experiments); LeastSquaresAccumulator (modelgen/estimation/accumulator.hpp)
// takes the same equations in blocks without storing W.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/estimation/estimation_error.hpp"

namespace modelgen {

struct LeastSquaresResult {
  Eigen::VectorXd value;           ///< estimated parameters (eq. 15), one per column of W
  Eigen::VectorXd std_dev;         ///< standard deviations (eq. 17-18)
  Eigen::VectorXd rel_std_dev;     ///< relative standard deviations in % (eq. 19); +inf for 0
  /// The inverse of the covariance of eq. 18, W'W / sigma^2 on the (weighted) equations: the
  /// metric in which a constrained estimate's distance from `value` is its cost
  /// (modelgen/estimation/physical.hpp).
  Eigen::MatrixXd information;
  long long equations = 0;  ///< rows of W: the weighted sum of squares is (equations - b) sigma^2
  double residual_std_dev = 0;     ///< sigma_rho of the (weighted) equations (eq. 17)
  double condition_number = 0;     ///< of the (weighted) W, 2-norm
  double relative_error_norm = 0;  ///< ||Y - W value|| / ||Y|| on the unweighted equations
  /// WLS: the standard deviation of each group's equation error from its OLS solution (eq. 20),
  /// the inverse of the group's weight. OLS: empty.
  std::vector<double> group_std_dev;
  /// Empty: std_dev is eq. 18's. Else which covariance replaced it and why (the equation errors
  /// are correlated: a sandwich, runtime/src/estimation/correlated_covariance.hpp).
  std::string covariance;
};

/// Ordinary least squares (Gautier & Briot eq. 15-19). `W` is r x b (r stacked equations,
/// b parameters), `y` has r entries; `names` (b entries) name the columns in messages.
/// Solved by Householder QR over blocks of rows (no copy of W, never forming W^T W), rank and
/// statistics from a column-pivoted QR of the small triangular factor; two threads for large W.
/// Extra memory O(b (b + 256)) whatever r.
/// Throws EstimationError on mismatched sizes, non-finite entries (naming row and column),
/// r <= b, or rank deficiency; the message names the parameters the data do not excite or
/// cannot tell apart.
LeastSquaresResult fit_ols(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                           const std::vector<std::string>& names);

/// Weighted least squares (eq. 20): each equation belongs to a group (for the IDIM, the joint
/// of the row, or joint and experiment); every group is weighted by the inverse of the standard
/// deviation of its error in the OLS solution of that group's equations, then OLS is solved on
/// the weighted system. `group` has r entries, values 0..G-1, every group needing more
/// equations than parameters (than the parameters it sees: columns that are zero in all of a
/// group's rows are left out of its own solution). One pass over W computes both the groups'
/// errors and the weighted solution; extra memory O(G b (b + 256)) at most, and no more than
/// about twice W's. Throws EstimationError as fit_ols does.
LeastSquaresResult fit_wls(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                           const std::vector<int>& group, const std::vector<std::string>& names);

}  // namespace modelgen
