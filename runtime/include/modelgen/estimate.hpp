// Linear least-squares identification with the statistics of Gautier & Briot (eq. 15-20):
// ordinary and weighted least squares on a stacked observation matrix, standard deviations and
// relative standard deviations of the estimates, and essential parameters by iterative
// elimination. Works on any W (IDIM regressor rows, PIM power rows, several experiments).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace modelgen {

/// Bad estimation input: sizes that do not match, NaN/inf, fewer rows than parameters, or a
/// rank-deficient W. what() says which, in words.
class EstimationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LeastSquaresResult {
  Eigen::VectorXd value;           ///< estimated parameters (eq. 15), one per column of W
  Eigen::VectorXd std_dev;         ///< standard deviations (eq. 17-18)
  Eigen::VectorXd rel_std_dev;     ///< relative standard deviations in % (eq. 19); +inf for 0
  double residual_std_dev = 0;     ///< sigma_rho of the (weighted) equations (eq. 17)
  double condition_number = 0;     ///< of the (weighted) W, 2-norm
  double relative_error_norm = 0;  ///< ||Y - W value|| / ||Y|| on the unweighted equations
  /// WLS: the standard deviation of each group's equation error from its OLS solution (eq. 20),
  /// the inverse of the group's weight. OLS: empty.
  std::vector<double> group_std_dev;
};

/// Ordinary least squares (Gautier & Briot eq. 15-19). `W` is r x b (r stacked equations,
/// b parameters), `y` has r entries; `names` (b entries) name the columns in messages.
/// Solved by QR with column pivoting, never forming W^T W; memory O(r b).
/// Throws EstimationError on mismatched sizes, non-finite entries, r <= b, or rank deficiency;
/// the message names the parameters the data do not excite or cannot tell apart.
LeastSquaresResult fit_ols(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                           const std::vector<std::string>& names);

/// Weighted least squares (eq. 20): each equation belongs to a group (for the IDIM, the joint
/// of the row, or joint and experiment); every group is weighted by the inverse of the standard
/// deviation of its error in the OLS solution of that group's equations, then OLS is solved on
/// the weighted system. `group` has r entries, values 0..G-1, every group needing more
/// equations than parameters. Throws EstimationError as fit_ols does.
LeastSquaresResult fit_wls(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                           const std::vector<int>& group, const std::vector<std::string>& names);

struct EssentialParameters {
  std::vector<int> kept;        ///< column indices of the essential parameters, ascending
  std::vector<int> eliminated;  ///< in elimination order
  LeastSquaresResult fit;       ///< the estimate on the kept columns
};

/// Essential parameters (Pham & Gautier, as used by Gautier & Briot): starting from all
/// columns, repeatedly drop the one with the largest relative standard deviation until the
/// ratio of the largest to the smallest relative standard deviation is below `r_sigma`.
/// Fits with WLS when `group` is non-empty, else OLS.
EssentialParameters essential_parameters(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                                         const std::vector<int>& group,
                                         const std::vector<std::string>& names,
                                         double r_sigma = 20.0);

}  // namespace modelgen
