// Stage 1 of the projection method on one record: the least-squares non-causal FIR from the
// references to the torque (Bona & Curatella eq. 10-11), the standard deviations of its
// coefficients and the decorrelation test of its residual against the references' lags.

#include "runtime/src/closed_loop/fir_projection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/QR>

#include "modelgen/closed_loop/projection_method.hpp"
#include "modelgen/estimation/estimation_error.hpp"

namespace modelgen {

namespace {

using detail::kHeld;

// Two-sided 99 % point of the standard normal: a white-noise correlation of N samples stays
// within kBand99 / sqrt(N) with 99 % probability.
constexpr double kBand99 = 2.58;
// Singular values of the column-scaled regressor below this fraction of the largest are
// treated as zero: a periodic reference of H harmonics makes its lags exactly dependent.
constexpr double kRankThreshold = 1e-10;

// The z with P(|N(0,1)| > z) = p, by bisection on erfc (monotone).
double normal_two_sided(double p) {
  double low = 0, high = 40;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (low + high);
    (std::erfc(mid / std::sqrt(2.0)) > p ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

// The regressor of eq. 10 for lags -M..M of the moving references, after the constant.
Eigen::MatrixXd fir_regressor(const LaggedReferences& references, const std::vector<int>& moving,
                              int lags) {
  const Eigen::Index rows = references.constant.size();
  Eigen::MatrixXd phi(rows, 1 + static_cast<Eigen::Index>(moving.size()) * (2 * lags + 1));
  phi.col(0) = references.constant;
  Eigen::Index column = 1;
  for (const int i : moving) {
    for (int k = -lags; k <= lags; ++k) phi.col(column++) = references.at(k).col(i);
  }
  return phi;
}

double correlation(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::VectorXd x = a.array() - a.mean(), y = b.array() - b.mean();
  const double norms = x.norm() * y.norm();
  return norms > 0 ? x.dot(y) / norms : 0.0;
}

// Throws unless the references reach the lags the test of M = `lags` needs and match the
// torques' rows; returns that window.
int check_fir_inputs(const Eigen::MatrixXd& u, const LaggedReferences& references, int lags) {
  if (lags < 0) throw EstimationError("FIR projection: lags " + std::to_string(lags) + " < 0");
  const int window = decorrelation_window(lags);
  if (references.max_lag < window ||
      references.by_lag.size() != static_cast<std::size_t>(2 * references.max_lag + 1)) {
    throw EstimationError(
        "FIR projection: the references reach lag " + std::to_string(references.max_lag) +
        ", the test of M = " + std::to_string(lags) + " needs " + std::to_string(window));
  }
  const Eigen::Index rows = u.rows();
  for (const Eigen::MatrixXd& r : references.by_lag) {
    if (r.rows() != rows || r.cols() != references.at(0).cols()) {
      throw EstimationError("FIR projection: the references have " + std::to_string(r.rows()) +
                            " rows, the torques " + std::to_string(rows));
    }
  }
  if (references.constant.size() != rows) {
    throw EstimationError("FIR projection: the constant regressor does not match the torques");
  }
  return window;
}

// The references that are not held.
std::vector<int> moving_references(const LaggedReferences& references) {
  std::vector<int> moving;
  for (Eigen::Index i = 0; i < references.at(0).cols(); ++i) {
    const Eigen::VectorXd r = references.at(0).col(i);
    const double range = r.maxCoeff() - r.minCoeff();
    if (range > kHeld * std::max(1.0, r.cwiseAbs().maxCoeff()))
      moving.push_back(static_cast<int>(i));
  }
  return moving;
}

// Least squares of eq. 11 on the column-scaled regressor `phi`: coefficients, projected torque,
// rank, residual squares and, at full rank, the coefficients' standard deviations.
void solve_fir(const Eigen::MatrixXd& u, const Eigen::MatrixXd& phi, FirProjection& out) {
  const Eigen::Index rows = u.rows();
  const Eigen::Index p = phi.cols();
  const Eigen::VectorXd scale = phi.colwise().norm().cwiseMax(1e-300).cwiseInverse();
  const Eigen::MatrixXd scaled = phi * scale.asDiagonal();
  // The threshold before the decomposition: the complete orthogonal step uses the rank.
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(scaled.rows(), scaled.cols());
  cod.setThreshold(kRankThreshold);
  cod.compute(scaled);
  out.coefficients = scale.asDiagonal() * cod.solve(u);
  out.projected = phi * out.coefficients;
  out.rank = cod.rank();
  out.full_rank = out.rank == p;
  const Eigen::MatrixXd residual = u - out.projected;
  out.residual_squares = residual.colwise().squaredNorm().transpose();
  out.coefficient_std =
      Eigen::MatrixXd::Constant(p, u.cols(), std::numeric_limits<double>::quiet_NaN());
  if (out.full_rank && rows > p) {
    const Eigen::MatrixXd inverse =
        (scaled.transpose() * scaled).ldlt().solve(Eigen::MatrixXd::Identity(p, p));
    const Eigen::VectorXd unit = scale.cwiseProduct(inverse.diagonal().cwiseMax(0).cwiseSqrt());
    for (Eigen::Index j = 0; j < u.cols(); ++j) {
      const double sigma = std::sqrt(residual.col(j).squaredNorm() / static_cast<double>(rows - p));
      out.coefficient_std.col(j) = sigma * unit;
    }
  }
}

// The correlations of the residual u~ with the moving references' lags beyond M, up to
// `window`, against the band of white noise.
DecorrelationTest decorrelation_test(const Eigen::MatrixXd& residual,
                                     const LaggedReferences& references,
                                     const std::vector<int>& moving, int lags, int window) {
  DecorrelationTest test;
  test.window = window;
  test.tested = static_cast<long long>(residual.cols()) * static_cast<long long>(moving.size()) *
                2 * (window - lags);
  const double root_n = std::sqrt(static_cast<double>(residual.rows()));
  test.single_band = kBand99 / root_n;
  // Sidak: each correlation at the level that leaves all m within the band 99 times in 100.
  const double each = 1 - std::pow(0.99, 1.0 / static_cast<double>(std::max(test.tested, 1LL)));
  test.band = normal_two_sided(each) / root_n;
  for (Eigen::Index j = 0; j < residual.cols(); ++j) {
    for (const int i : moving) {
      for (int k = -window; k <= window; ++k) {
        if (std::abs(k) <= lags) continue;  // zero by construction
        const double c = std::abs(correlation(residual.col(j), references.at(k).col(i)));
        if (c > test.worst) {
          test.worst = c;
          test.worst_channel = static_cast<int>(j);
          test.worst_reference = i;
          test.worst_lag = k;
        }
      }
    }
  }
  return test;
}

}  // namespace

FirProjection fit_fir_projection(const Eigen::MatrixXd& u, const LaggedReferences& references,
                                 int lags) {
  const int window = check_fir_inputs(u, references, lags);
  const Eigen::Index rows = u.rows();
  FirProjection out;
  out.lags = lags;
  out.moving = moving_references(references);
  // The constant: a linear FIR about the record's mean posture leaves an offset (gravity at
  // that posture, the friction's mean) that the references' lags would otherwise have to
  // imitate through their own means, bending the filter.
  const Eigen::MatrixXd phi = fir_regressor(references, out.moving, lags);
  const Eigen::Index p = phi.cols();
  if (rows < kMinRowsPerCoefficient * p) {
    throw EstimationError("FIR projection: " + std::to_string(rows) + " rows for " +
                          std::to_string(p) + " FIR coefficients (M = " + std::to_string(lags) +
                          "); at least " + std::to_string(kMinRowsPerCoefficient) +
                          " rows per coefficient are needed: choose a smaller M");
  }
  solve_fir(u, phi, out);
  out.test = decorrelation_test(u - out.projected, references, out.moving, lags, window);
  return out;
}

}  // namespace modelgen
