// Linear least-squares identification with the statistics of Gautier & Briot (eq. 15-20):
// ordinary and weighted least squares on a stacked observation matrix, standard deviations and
// relative standard deviations of the estimates, and essential parameters by iterative
// elimination. Works on any W (IDIM regressor rows, PIM power rows, several experiments), given
// whole or streamed in blocks through LeastSquaresAccumulator, which never stores W.
#pragma once

#include <memory>
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
/// Solved by Householder QR over blocks of rows (no copy of W, never forming W^T W), rank and
/// statistics from a column-pivoted QR of the small triangular factor; two threads for large W.
/// Extra memory O(b (b + 1024)) whatever r.
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
/// errors and the weighted solution; extra memory O(G b (b + 1024)) at most, and no more than
/// about twice W's. Throws EstimationError as fit_ols does.
LeastSquaresResult fit_wls(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                           const std::vector<int>& group, const std::vector<std::string>& names);

/// Equations y = W beta fed in blocks of rows, in groups, without ever storing W: each group's
/// rows are reduced as they arrive to the triangular factor R_g of [W_g y_g] (Householder QR of
/// the previous factor stacked on the new rows, over only the columns the group has seen
/// nonzero). Memory per group O(c_g (c_g + 1024)), c_g <= b its seen columns, whatever the
/// number of rows. Since [W_g y_g] = Q_g R_g with orthonormal Q_g, every statistic of
/// fit_ols/fit_wls (eq. 15-20) follows from the factors, and so do ||y_g - W_g beta|| for any
/// beta. Not thread-safe, const members included (they finish pending reductions): give each
/// thread its own accumulator, then merge().
class LeastSquaresAccumulator {
 public:
  /// `params` unknowns (b, the columns of W), `groups` groups of equations (>= 1).
  /// Throws EstimationError for a size below 1.
  LeastSquaresAccumulator(int params, int groups);
  ~LeastSquaresAccumulator();
  LeastSquaresAccumulator(LeastSquaresAccumulator&& other) noexcept;
  LeastSquaresAccumulator& operator=(LeastSquaresAccumulator&& other) noexcept;

  int params() const;
  int groups() const;
  /// Names for the groups in error messages (e.g. "run1.csv, joint 2"), one per group;
  /// default "group g".
  void name_groups(std::vector<std::string> labels);
  /// Equations added to `group` (or to all groups).
  Eigen::Index rows(int group) const;
  Eigen::Index rows() const;

  /// Adds `count` equations to `group`: equation i is y[i * y_stride] = sum over k < params() of
  /// W[i * row_stride + k * col_stride] beta_k. A row-major block of rows has col_stride 1, a
  /// column-major one row_stride 1 and col_stride its leading dimension. Nothing is copied
  /// beyond the group's current block. Non-finite values are found when fitting (they reach the
  /// factor). Throws EstimationError for a group out of range or a negative count.
  void add(int group, Eigen::Index count, const double* W, Eigen::Index row_stride,
           Eigen::Index col_stride, const double* y, Eigen::Index y_stride);
  /// Reduces the rows not yet reduced and frees the groups' row buffers (a group fed again gets
  /// a new one): call it when groups are complete, e.g. after each experiment.
  void compact();
  /// Adds all equations of `other` (same params() and groups()), e.g. rows another thread
  /// reduced; `other` is left empty. Throws EstimationError if the sizes differ.
  void merge(LeastSquaresAccumulator&& other);

  /// ||y_g|| of one group's equations.
  double y_norm(int group) const;
  /// ||y_g - W_g beta|| of one group's equations; beta has params() entries.
  double residual_norm(int group, const Eigen::VectorXd& beta) const;

  /// fit_ols on all equations added (the groups only matter to fit_wls). `names`: params()
  /// entries. Throws EstimationError as fit_ols does; non-finite input is named by group.
  LeastSquaresResult fit_ols(const std::vector<std::string>& names) const;
  /// fit_wls with the accumulator's groups (eq. 20). Throws EstimationError as fit_wls does,
  /// also for a group with no equations.
  LeastSquaresResult fit_wls(const std::vector<std::string>& names) const;

  /// The same fits restricted to the columns `kept` (ascending indices below params()), as if
  /// W had only those: what essential_parameters needs, at the cost of small factorizations.
  LeastSquaresResult fit(const std::vector<int>& kept, const std::vector<std::string>& kept_names,
                         bool weighted) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

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
