// The information criteria of excitation design on a stacked base regressor W (samples x dof
// rows, base-parameter columns): the condition number (Bona & Curatella eq. 20, Presse &
// Gautier) and -log det(W^T W) (d-optimality, Swevers et al. 1997), of W D with a fixed
// column scale D. Unscaled, parameters in kg, kg m, kg m^2 and N m s make the condition number
// mostly a measure of units. Scaling each column to unit norm at the point evaluated removes
// the units but also hides how strongly a parameter is excited (a joint that barely moves
// keeps unit-norm columns); a scale fixed before the optimisation (excitation_design: the RMS
// column norms of the random starts) removes the units and keeps that.
#pragma once

#include <Eigen/Core>

namespace modelgen {

enum class DesignCriterion { kCond, kLogDet };

/// The criterion and what the report needs, for one stacked regressor.
struct CriterionValue {
  double value = 0;  ///< log cond(W D) or -log det((W D)^T (W D)), D = diag(1 / scale)
  double cond_scaled = 0;      ///< cond(W D)
  double cond_unit = 0;        ///< cond of W with unit-norm columns
  double cond_unscaled = 0;    ///< cond(W)
  double sigma_min_scaled = 0, sigma_min_unscaled = 0;
  /// d value / d W (same shape as W); filled when asked.
  Eigen::MatrixXd gradient;
  /// The same gradient in factors, filled with it: d value / d W = W F diag(w) F^T with
  /// F = `gradient_factor` (columns x r) and w = `gradient_weight` (r). r = 2 for cond (the
  /// extreme eigenvectors), the number of columns for logdet: a caller differentiating W in
  /// something else may contract with r directions of W instead of with every row.
  Eigen::MatrixXd gradient_factor;
  Eigen::VectorXd gradient_weight;
};

/// The criterion of `W` with columns divided by `scale` (positive, one per column). The cond
/// criterion is the log of the condition number: the same minimiser, a better-scaled function.
/// A rank-deficient W gives +inf. With `with_gradient`, d value / d W from the
/// eigen-decomposition of (W D)^T (W D): d lambda_i = 2 (W D v_i)^T dW D v_i.
CriterionValue evaluate_criterion(const Eigen::MatrixXd& W, const Eigen::VectorXd& scale,
                                  DesignCriterion criterion, bool with_gradient);

/// The two columns of W whose directions are closest, and the condition number no column
/// scaling can bring W below because of them: for unit columns u, v with correlation
/// rho = |u . v|, the 2-column block [u v] has singular values sqrt(1 +- rho), so
/// cond(W D) >= sqrt((1 + rho) / (1 - rho)) for every diagonal D > 0 (interlacing: W's
/// extreme singular values enclose those of any block of its columns; scaling a column does
/// not change its direction, and the bound for [a u, b v] is smallest at a = b).
struct CollinearPair {
  int first = -1, second = -1;  ///< column indices, first < second
  double correlation = 0;       ///< |cos| of the angle between them
  double cond_floor = 1;        ///< sqrt((1 + correlation) / (1 - correlation))
};

/// The most collinear pair of W's columns (at least two, none zero).
CollinearPair most_collinear_pair(const Eigen::MatrixXd& W);

}  // namespace modelgen
