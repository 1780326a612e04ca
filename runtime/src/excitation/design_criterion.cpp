// Condition number and d-optimality of a stacked regressor, with the gradient in W.

#include "modelgen/excitation/design_criterion.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

namespace modelgen {

namespace {

double condition_number(const Eigen::MatrixXd& W, double* sigma_min) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(W.transpose() * W, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  *sigma_min = std::sqrt(std::max(lambda[0], 0.0));
  return lambda[0] > 0 ? std::sqrt(lambda[lambda.size() - 1] / lambda[0])
                       : std::numeric_limits<double>::infinity();
}

}  // namespace

CriterionValue evaluate_criterion(const Eigen::MatrixXd& W, DesignCriterion criterion,
                                  bool with_gradient) {
  CriterionValue out;
  const Eigen::VectorXd norms = W.colwise().norm().transpose();
  if ((norms.array() <= 0).any()) {
    out.value = out.cond_scaled = out.cond_unscaled = std::numeric_limits<double>::infinity();
    if (with_gradient) out.gradient = Eigen::MatrixXd::Zero(W.rows(), W.cols());
    return out;
  }
  const Eigen::MatrixXd scaled = W * norms.cwiseInverse().asDiagonal();
  out.cond_unscaled = condition_number(W, &out.sigma_min_unscaled);
  // The eigen-decomposition of the scaled information matrix: lambda_i = sigma_i^2.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(scaled.transpose() * scaled);
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const Eigen::Index p = lambda.size();
  out.sigma_min_scaled = std::sqrt(std::max(lambda[0], 0.0));
  if (!(lambda[0] > 0)) {
    out.value = out.cond_scaled = std::numeric_limits<double>::infinity();
    if (with_gradient) out.gradient = Eigen::MatrixXd::Zero(W.rows(), W.cols());
    return out;
  }
  out.cond_scaled = std::sqrt(lambda[p - 1] / lambda[0]);
  // value = g(lambda); Q = V diag(dg/dlambda) V^T, so that d value / d(W D) = 2 (W D) Q.
  Eigen::MatrixXd Q;
  const Eigen::MatrixXd& V = eig.eigenvectors();
  if (criterion == DesignCriterion::kCond) {
    out.value = std::log(out.cond_scaled);  // (log lambda_max - log lambda_min) / 2
    if (with_gradient) {
      Q = V.col(p - 1) * V.col(p - 1).transpose() / (2 * lambda[p - 1]) -
          V.col(0) * V.col(0).transpose() / (2 * lambda[0]);
    }
  } else {
    out.value = -lambda.array().log().sum();
    if (with_gradient) Q = -V * lambda.cwiseInverse().asDiagonal() * V.transpose();
  }
  if (!with_gradient) return out;
  const Eigen::MatrixXd by_scaled = 2 * scaled * Q;  // d value / d(W D)
  // Column c of W D is w_c / |w_c|: its derivative in w_c is (I - u u^T) / |w_c|, u = w_c/|w_c|.
  out.gradient.resize(W.rows(), W.cols());
  for (Eigen::Index c = 0; c < W.cols(); ++c) {
    const Eigen::VectorXd u = scaled.col(c);
    const Eigen::VectorXd g = by_scaled.col(c);
    out.gradient.col(c) = (g - u * u.dot(g)) / norms[c];
  }
  return out;
}

}  // namespace modelgen
