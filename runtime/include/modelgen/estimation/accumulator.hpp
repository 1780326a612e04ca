// Least-squares equations streamed in blocks of rows and groups, reduced as they arrive to small
// triangular factors (TSQR), from which every fit and statistic of least_squares.hpp follows.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/least_squares.hpp"

namespace modelgen {

/// Equations y = W beta fed in blocks of rows, in groups, without ever storing W: each group's
/// rows are reduced as they arrive to the triangular factor R_g of [W_g y_g] (Householder QR of
/// the previous factor stacked on the new rows, over only the columns the group has seen
/// nonzero). Memory per group O(c_g (c_g + 256)), c_g <= b its seen columns, whatever the
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

}  // namespace modelgen
