// The information criteria of excitation design on a stacked base regressor W (samples x dof
// rows, base-parameter columns): the condition number (Bona & Curatella eq. 20, Presse &
// Gautier) and -log det(W^T W) (d-optimality, Swevers et al. 1997). Columns are scaled to unit
// norm first: parameters come in kg, kg m and kg m^2 and friction in N m s, and an unscaled
// condition number mostly measures those units, not the excitation (Presse & Gautier).
#pragma once

#include <Eigen/Core>

namespace modelgen {

enum class DesignCriterion { kCond, kLogDet };

/// The criterion and what the report needs, for one stacked regressor.
struct CriterionValue {
  double value = 0;           ///< log cond(W D), or -log det((W D)^T (W D)); D: unit columns
  double cond_scaled = 0;     ///< cond(W D)
  double cond_unscaled = 0;   ///< cond(W)
  double sigma_min_scaled = 0, sigma_min_unscaled = 0;
  /// d value / d W (same shape as W), through the column scaling; filled when asked.
  Eigen::MatrixXd gradient;
};

/// The criterion of `W` (full column rank expected: a rank-deficient W gives +inf). The cond
/// criterion is the log of the condition number: the same minimiser, a better-scaled function.
/// With `with_gradient`, d value / d W from the eigen-decomposition of (W D)^T (W D):
/// d lambda_i = 2 (W D v_i)^T dW' v_i, then through D = diag(1 / |w_c|).
CriterionValue evaluate_criterion(const Eigen::MatrixXd& W, DesignCriterion criterion,
                                  bool with_gradient);

}  // namespace modelgen
