// The errors-in-variables library's access to ErrorsInVariablesObjective's insides
// (errors_in_variables.cpp, errors_in_variables_score.cpp).
#pragma once

#include <optional>

#include <Eigen/Core>

#include "modelgen/estimation/errors_in_variables.hpp"

namespace modelgen {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// S_ML^2 of one sample (Bona & Curatella eq. 16), the covariance of its equation error: with
/// B = [-Js, I], B Sigma B' = M Js' + D_tau, M = (d tau / d x) Sigma_x over the state part, from
/// the state Jacobian `Js` (n x 3n) and the sample's noise `v`. `M` (n x 3n) is work space.
inline void equation_error_covariance(const RowMajorMatrix& Js, const PeriodicNoise& v,
                                      Eigen::MatrixXd& M, Eigen::MatrixXd& S2) {
  const Eigen::Index n = Js.rows();
  for (Eigen::Index j = 0; j < n; ++j) {
    M.col(j) = Js.col(j) * v.q[j] + Js.col(2 * n + j) * v.q_ddq[j];
    M.col(n + j) = Js.col(n + j) * v.dq[j];
    M.col(2 * n + j) = Js.col(2 * n + j) * v.ddq[j] + Js.col(j) * v.q_ddq[j];
  }
  S2 = M * Js.transpose();
  S2.diagonal() += v.tau;
}

struct ErrorsInVariablesAccess {
  // Residuals (and Jacobian rows) of samples [begin, end) into r and J at row (begin * dof).
  static bool evaluate_block(const ErrorsInVariablesObjective& o, const double* theta,
                             Eigen::Index begin, Eigen::Index end, double* r, double* J);
  // Covariance of the score J' r at theta from the noise of the observations, linearised;
  // nullopt when the noise has no lines (errors_in_variables_score.cpp).
  static std::optional<Eigen::MatrixXd> score_covariance(const ErrorsInVariablesObjective& o,
                                                         const Eigen::VectorXd& theta,
                                                         const Eigen::MatrixXd& J);
};

}  // namespace modelgen
