// Condition number and d-optimality of a stacked regressor, with the gradient in W.

#include "modelgen/excitation/design_criterion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

namespace modelgen {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// cond(M) from the eigenvalues of M^T M; the smallest singular value in `sigma_min`.
double condition_number(const Eigen::MatrixXd& M, double* sigma_min) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M.transpose() * M, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  if (sigma_min != nullptr) *sigma_min = std::sqrt(std::max(lambda[0], 0.0));
  return lambda[0] > 0 ? std::sqrt(lambda[lambda.size() - 1] / lambda[0]) : kInfinity;
}

}  // namespace

CriterionValue evaluate_criterion(const Eigen::MatrixXd& W, const Eigen::VectorXd& scale,
                                  DesignCriterion criterion, bool with_gradient) {
  CriterionValue out;
  if (with_gradient) out.gradient = Eigen::MatrixXd::Zero(W.rows(), W.cols());
  out.cond_unscaled = condition_number(W, &out.sigma_min_unscaled);
  const Eigen::VectorXd norms = W.colwise().norm().transpose();
  out.cond_unit = (norms.array() > 0).all()
                      ? condition_number(W * norms.cwiseInverse().asDiagonal(), nullptr)
                      : kInfinity;
  const Eigen::MatrixXd scaled = W * scale.cwiseInverse().asDiagonal();
  // The eigen-decomposition of the scaled information matrix: lambda_i = sigma_i^2.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(scaled.transpose() * scaled);
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const Eigen::Index p = lambda.size();
  out.sigma_min_scaled = std::sqrt(std::max(lambda[0], 0.0));
  if (!(lambda[0] > 0)) {
    out.value = out.cond_scaled = kInfinity;
    return out;
  }
  out.cond_scaled = std::sqrt(lambda[p - 1] / lambda[0]);
  // value = g(lambda); with Q = V diag(dg/dlambda) V^T, d value / d(W D) = 2 (W D) Q, so
  // d value / d W = W F diag(w) F^T with F = D V' and w = 2 dg/dlambda over the eigenvectors
  // V' that g depends on.
  const Eigen::MatrixXd& V = eig.eigenvectors();
  Eigen::MatrixXd vectors;
  if (criterion == DesignCriterion::kCond) {
    out.value = std::log(out.cond_scaled);  // (log lambda_max - log lambda_min) / 2
    vectors.resize(p, 2);
    vectors << V.col(p - 1), V.col(0);
    out.gradient_weight = Eigen::Vector2d(1 / lambda[p - 1], -1 / lambda[0]);
  } else {
    out.value = -lambda.array().log().sum();
    vectors = V;
    out.gradient_weight = -2 * lambda.cwiseInverse();
  }
  if (with_gradient) {
    out.gradient_factor = scale.cwiseInverse().asDiagonal() * vectors;
    const Eigen::MatrixXd& F = out.gradient_factor;
    out.gradient = W * F * out.gradient_weight.asDiagonal() * F.transpose();
  } else {
    out.gradient_weight.resize(0);
  }
  return out;
}

CollinearPair most_collinear_pair(const Eigen::MatrixXd& W) {
  const Eigen::VectorXd norms = W.colwise().norm().transpose();
  const Eigen::MatrixXd U = W * norms.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd cosines = U.transpose() * U;
  CollinearPair pair;
  for (Eigen::Index i = 0; i < cosines.rows(); ++i) {
    for (Eigen::Index j = i + 1; j < cosines.cols(); ++j) {
      if (std::abs(cosines(i, j)) > pair.correlation || pair.first < 0) {
        pair.first = static_cast<int>(i), pair.second = static_cast<int>(j);
        pair.correlation = std::min(std::abs(cosines(i, j)), 1.0);
      }
    }
  }
  pair.cond_floor = pair.correlation < 1 ? std::sqrt((1 + pair.correlation) / (1 - pair.correlation)) : kInfinity;
  return pair;
}

}  // namespace modelgen
