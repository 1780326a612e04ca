// Expected standard deviations of a design: (W^T W)^-1 = R^-1 R^-T from W = Q R.

#include "modelgen/excitation/expected_precision.hpp"

#include <stdexcept>

#include <Eigen/QR>

namespace modelgen {

Eigen::VectorXd expected_std_devs(const Eigen::MatrixXd& W, double noise) {
  if (!(noise > 0)) throw std::invalid_argument("expected_std_devs: the noise must be positive");
  if (W.rows() < W.cols()) {
    throw std::invalid_argument("expected_std_devs: fewer equations than parameters");
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(W);
  if (qr.rank() < W.cols()) {
    throw std::invalid_argument("expected_std_devs: the regressor has deficient column rank");
  }
  const Eigen::Index n = W.cols();
  // W P = Q R, so (W^T W)^-1 = P R^-1 R^-T P^T: row i of P R^-1 has the norm sd_i / noise.
  const Eigen::MatrixXd R = qr.matrixR().topLeftCorner(n, n).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd R_inverse =
      R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(n, n));
  const Eigen::MatrixXd rows = qr.colsPermutation() * R_inverse;
  return noise * rows.rowwise().norm();
}

}  // namespace modelgen
