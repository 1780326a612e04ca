// The standard deviations of IDIM-IV and DIDIM on correlated equation errors (issue 31): the
// decimated rows of a filtered closed-loop record keep a correlation from row to row (the
// controller answers its own noise, and the filter spreads it), which the white-error formulas
// of closed_loop_identification.hpp ignore. Both estimates are the solution of a linear system
// A beta = X^T y at their last iteration, so their covariance is the sandwich
// A^-1 (X^T Omega X) A^-T with the score covariance X^T Omega X from the residuals by
// Newey-West (correlated_covariance.hpp):
//   IV (Janot et al. 2014, the IV covariance of their eq. 27 generalised): X = Z the
//     instruments, A = Z^T W, residual y - W beta;
//   DIDIM (Gautier et al. 2013, the Gauss-Newton covariance of their eq. 19 generalised):
//     X = W_s the simulated regressor, A = W_s^T W_s, residual the output error y - tau_s.

#include "runtime/src/closed_loop/closed_loop_covariance.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "runtime/src/estimation/correlated_covariance.hpp"

namespace modelgen::detail {

void closed_loop_sandwich(const std::vector<RecordEquations>& equations,
                          const std::vector<std::vector<Eigen::MatrixXd>>& X,
                          const std::vector<std::vector<Eigen::MatrixXd>>& W,
                          const std::vector<std::vector<Eigen::VectorXd>>& residual,
                          LeastSquaresResult& fit) {
  const Eigen::Index b = fit.value.size();
  std::vector<ResidualGroup> groups;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(b, b);
  for (std::size_t e = 0; e < equations.size(); ++e) {
    for (std::size_t j = 0; j < X[e].size(); ++j) {
      const double w = equations[e].weight[j];
      ResidualGroup group;
      group.X = w * X[e][j];
      group.r = w * residual[e][j];
      A += group.X.transpose() * (w * W[e][j]);
      groups.push_back(std::move(group));
    }
  }
  const SandwichCovariance score = score_covariance(groups);
  if (score.description.empty()) return;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  if (!lu.isInvertible()) return;
  const Eigen::MatrixXd A_inverse = lu.inverse();
  const Eigen::MatrixXd covariance = A_inverse * score.meat * A_inverse.transpose();
  fit.std_dev = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  fit.information = covariance.ldlt().solve(Eigen::MatrixXd::Identity(b, b));
  fit.covariance = score.description;
}

}  // namespace modelgen::detail
