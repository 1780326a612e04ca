// The standard deviations of physical_std_dev.hpp: the free directions at the optimum in the
// log-Cholesky parameters (Rucker & Wensing 2022), differentiated by Ceres' jets.

#include "runtime/src/estimation/physical_std_dev.hpp"

#include <ceres/jet.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cstddef>
#include <vector>

#include "modelgen/model/pseudo_inertia.hpp"

namespace modelgen::detail {

Eigen::VectorXd base_standard_deviations(const Layout& layout, const std::vector<char>& binding,
                                         const Eigen::MatrixXd& K, const Eigen::MatrixXd& U,
                                         const Eigen::MatrixXd& G, const Eigen::MatrixXd& T,
                                         const Eigen::VectorXd& d,
                                         const Eigen::VectorXd& standard) {
  const Eigen::Index n = K.cols();
  if (std::find(binding.begin(), binding.end(), 1) == binding.end()) {
    const Eigen::MatrixXd covariance = (U.transpose() * U).inverse();
    return covariance.diagonal().cwiseSqrt();
  }
  std::vector<Eigen::VectorXd> columns;  // d standard / d free, one per free direction
  for (int k : layout.scalar_params) {
    if (!binding[static_cast<std::size_t>(k)]) columns.push_back(Eigen::VectorXd::Unit(n, k));
  }
  for (const auto& index : layout.body_params) {
    if (binding[static_cast<std::size_t>(index[0])]) continue;
    double p[10];
    for (int s = 0; s < 10; ++s) p[s] = standard[index[s]];
    const auto theta = log_cholesky_from_inertial(p);
    if (!theta) continue;
    using Jet = ceres::Jet<double, 10>;
    Jet t[10], q[10];
    for (int i = 0; i < 10; ++i) t[i] = Jet((*theta)[i], i);
    inertial_from_log_cholesky(t, q);
    for (int i = 0; i < 10; ++i) {
      Eigen::VectorXd column = Eigen::VectorXd::Zero(n);
      for (int s = 0; s < 10; ++s) column[index[s]] = q[s].v[i];
      columns.push_back(column);
    }
  }
  Eigen::MatrixXd dp(n, static_cast<Eigen::Index>(columns.size()));
  for (std::size_t c = 0; c < columns.size(); ++c)
    dp.col(static_cast<Eigen::Index>(c)) = columns[c];
  // Residual Jacobian: the base term U K dp and the prior term G (in variables) back in standard
  // coordinates: G_std = G diag(d) T^-1.
  const Eigen::MatrixXd G_standard = G * d.asDiagonal() * T.inverse();
  Eigen::MatrixXd J(U.rows() + G.rows(), dp.cols());
  J << U * K * dp, G_standard * dp;
  // (J'J)^+ = J^+ J^+': from J itself, not the normal matrix, whose condition number is the
  // square of J's (a divergence body near the boundary has a steep Hessian): formed from J'J,
  // rounding raised base sds 1e-5 above the unconstrained ones.
  const Eigen::MatrixXd db = K * dp;
  const Eigen::MatrixXd root = db * J.completeOrthogonalDecomposition().pseudoInverse();
  const Eigen::MatrixXd F = U.transpose() * U;
  const Eigen::MatrixXd F_inverse = F.inverse();
  // The F-orthogonal projector onto the free base directions, db (U db)^+ U, from U db
  // itself: through db' F db a direction lost to rounding was counted in both parts.
  const Eigen::MatrixXd held = Eigen::MatrixXd::Identity(F.rows(), F.cols()) -
                               db * (U * db).completeOrthogonalDecomposition().pseudoInverse() * U;
  const Eigen::MatrixXd total = root * root.transpose() + held * F_inverse * held.transpose();
  return total.diagonal().cwiseMax(0.0).cwiseSqrt();
}

}  // namespace modelgen::detail
