// The prior term of physical_prior.hpp: group scales and the null space of the scaled
// regrouping map.

#include "runtime/src/estimation/physical_prior.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "modelgen/model/physical_consistency.hpp"
#include "modelgen/model/pseudo_inertia.hpp"

namespace modelgen::detail {

Eigen::VectorXd prior_scales(const RigidBodyTree& tree, const Layout& layout,
                             const Eigen::VectorXd& reference, const Eigen::MatrixXd& K,
                             const Eigen::VectorXd* base_std_dev) {
  std::vector<std::vector<int>> groups[3];  // inertias, first moments, masses
  for (const auto& index : layout.body_params) {
    groups[0].push_back({index[0], index[1], index[2], index[3], index[4], index[5]});
    groups[1].push_back({index[6], index[7], index[8]});
    groups[2].push_back({index[9]});
  }
  std::vector<std::vector<int>> by_kind(static_cast<std::size_t>(ParamKind::kFcm) + 1);
  for (int k : layout.scalar_params) {
    by_kind[static_cast<std::size_t>(tree.params[static_cast<std::size_t>(k)].kind)].push_back(k);
  }
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(reference.size());
  const auto largest_of = [&](const std::vector<int>& members) {
    double largest = 0;
    for (int k : members) largest = std::max(largest, std::abs(reference[k]));
    return largest;
  };
  for (const auto& cls : groups) {
    double class_largest = 0;
    for (const auto& members : cls) class_largest = std::max(class_largest, largest_of(members));
    for (const auto& members : cls) {
      const double size = std::max(largest_of(members), 1e-3 * class_largest);
      for (int k : members) scale[k] = size > 0 ? size : 1.0;
    }
  }
  for (const auto& members : by_kind) {
    const double size = largest_of(members);
    for (int k : members) scale[k] = size > 0 ? size : 1.0;
  }
  if (base_std_dev == nullptr) return scale;
  for (Eigen::Index k = 0; k < K.cols(); ++k) {
    double resolved = std::numeric_limits<double>::infinity();
    const double column = K.col(k).cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < K.rows(); ++j) {
      if (std::abs(K(j, k)) > 1e-9 * column) {
        resolved = std::min(resolved, (*base_std_dev)[j] / std::abs(K(j, k)));
      }
    }
    if (std::isfinite(resolved)) scale[k] = std::max(scale[k], resolved);
  }
  return scale;
}

Eigen::MatrixXd prior_metric_root(const Layout& layout, const Eigen::VectorXd& prior_value,
                                  const std::vector<char>& has_a_priori,
                                  const Eigen::VectorXd& scale) {
  Eigen::MatrixXd L = scale.cwiseInverse().asDiagonal();
  for (const auto& index : layout.body_params) {
    bool known = true;
    double p0[10];
    for (int s = 0; s < 10; ++s) {
      known = known && has_a_priori[static_cast<std::size_t>(index[s])];
      p0[s] = prior_value[index[s]];
    }
    if (!known) continue;
    const Eigen::Matrix4d P0 = pseudo_inertia(p0);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(P0);
    if (!(eig.eigenvalues()[0] > 1e-12 * eig.eigenvalues()[3])) continue;  // not a body
    const Eigen::Matrix4d P0_inverse = eig.operatorInverseSqrt() * eig.operatorInverseSqrt();
    std::array<Eigen::Matrix4d, 10> E;  // dP per unit change of each standard parameter
    for (int s = 0; s < 10; ++s) {
      double unit[10] = {};
      unit[s] = 1;
      E[static_cast<std::size_t>(s)] = P0_inverse * pseudo_inertia(unit);
    }
    Eigen::Matrix<double, 10, 10> Q;  // tr(P0^-1 E_i P0^-1 E_j)
    for (int i = 0; i < 10; ++i) {
      for (int j = 0; j < 10; ++j)
        Q(i, j) = (E[static_cast<std::size_t>(i)] * E[static_cast<std::size_t>(j)]).trace();
    }
    const Eigen::Matrix<double, 10, 10> root =
        Eigen::LLT<Eigen::Matrix<double, 10, 10>>(Q).matrixU();
    for (int i = 0; i < 10; ++i) {
      for (int j = 0; j < 10; ++j) L(index[i], index[j]) = root(i, j);
    }
  }
  return L;
}

Eigen::MatrixXd null_space_of(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M) {
  const Eigen::MatrixXd KM = K * M;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(KM, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  const double largest = s.size() > 0 ? s[0] : 0.0;
  Eigen::Index rank = 0;
  while (rank < s.size() && s[rank] > 1e-10 * largest) ++rank;
  return svd.matrixV().rightCols(KM.cols() - rank);
}

Eigen::MatrixXd scaled_null_space(const Eigen::MatrixXd& K, const Eigen::VectorXd& scale) {
  return null_space_of(K, scale.asDiagonal().toDenseMatrix());
}

}  // namespace modelgen::detail
