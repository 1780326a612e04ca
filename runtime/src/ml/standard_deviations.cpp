// The covariance of standard_deviations.hpp.

#include "runtime/src/ml/standard_deviations.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <limits>

namespace modelgen::detail {

// Covariance of the identifiable unknowns: s^2 (J^T J)^-1 on unit-norm columns by the SVD.
Eigen::VectorXd standard_deviations(const Eigen::MatrixXd& J, const std::vector<bool>& keep,
                                    double s2) {
  std::vector<Eigen::Index> live;
  for (Eigen::Index u = 0; u < J.cols(); ++u) {
    if (keep[u]) live.push_back(u);
  }
  Eigen::VectorXd out =
      Eigen::VectorXd::Constant(J.cols(), std::numeric_limits<double>::quiet_NaN());
  if (live.empty()) return out;
  Eigen::MatrixXd Js(J.rows(), static_cast<Eigen::Index>(live.size()));
  Eigen::VectorXd scale(static_cast<Eigen::Index>(live.size()));
  for (size_t c = 0; c < live.size(); ++c) {
    scale[c] = J.col(live[c]).norm();
    Js.col(c) = J.col(live[c]) / scale[c];
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js, Eigen::ComputeThinV);
  const Eigen::VectorXd inv = svd.singularValues().cwiseInverse();
  const Eigen::MatrixXd Vs = svd.matrixV() * inv.asDiagonal();
  for (size_t c = 0; c < live.size(); ++c) {
    out[live[c]] = std::sqrt(s2 * Vs.row(c).squaredNorm()) / scale[c];
  }
  return out;
}

}  // namespace modelgen::detail
