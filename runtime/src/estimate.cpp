// Least squares through a column-pivoted QR: the estimate and (W^T W)^-1 = P R^-1 R^-T P^T come
// from the same factorization, so neither W^T W nor any r x r matrix is ever formed.

#include "modelgen/estimate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/QR>
#include <Eigen/SVD>

namespace modelgen {

namespace {

void check_inputs(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                  const std::vector<std::string>& names) {
  if (W.rows() != y.size()) {
    throw EstimationError("W has " + std::to_string(W.rows()) + " rows but Y has " +
                          std::to_string(y.size()) + " entries");
  }
  if (static_cast<Eigen::Index>(names.size()) != W.cols()) {
    throw EstimationError("W has " + std::to_string(W.cols()) + " columns but " +
                          std::to_string(names.size()) + " parameter names were given");
  }
  if (!W.allFinite() || !y.allFinite()) {
    throw EstimationError("W or Y holds NaN or infinite values");
  }
  if (W.rows() <= W.cols()) {
    throw EstimationError("only " + std::to_string(W.rows()) + " equations for " +
                          std::to_string(W.cols()) + " parameters: more data are needed");
  }
}

// Names of the columns that are zero or combinations of earlier ones (in column order), for
// the message of a rank-deficient W.
std::string unidentifiable(const Eigen::MatrixXd& W, const std::vector<std::string>& names) {
  const double scale = W.cwiseAbs().maxCoeff();
  Eigen::MatrixXd Q(W.rows(), 0);
  std::ostringstream zero, dependent;
  for (Eigen::Index k = 0; k < W.cols(); ++k) {
    Eigen::VectorXd v = W.col(k);
    const double norm = v.norm();
    if (norm <= 1e-12 * scale * std::sqrt(static_cast<double>(W.rows()))) {
      zero << " " << names[k];
      continue;
    }
    for (int pass = 0; pass < 2; ++pass) v -= Q * (Q.transpose() * v);
    // Looser than the QR rank threshold, so that nearly dependent columns are named too.
    if (v.norm() <= 1e-7 * norm) {
      dependent << " " << names[k];
      continue;
    }
    Q.conservativeResize(Eigen::NoChange, Q.cols() + 1);
    Q.col(Q.cols() - 1) = v / v.norm();
  }
  std::string out;
  if (!zero.str().empty()) out += " not excited by the data:" + zero.str() + ".";
  if (!dependent.str().empty()) {
    out += " not separable from the parameters before them (the data move them together):" +
           dependent.str() + ".";
  }
  return out;
}

LeastSquaresResult solve(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                         const std::vector<std::string>& names) {
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(W);
  qr.setThreshold(1e-10);
  const Eigen::Index b = W.cols();
  if (qr.rank() < b) {
    throw EstimationError("W is rank-deficient (rank " + std::to_string(qr.rank()) + " of " +
                          std::to_string(b) + "):" + unidentifiable(W, names));
  }
  LeastSquaresResult result;
  result.value = qr.solve(y);
  const Eigen::VectorXd residual = y - W * result.value;
  // Eq. 17: unbiased estimate of the equation error's variance.
  const double variance = residual.squaredNorm() / static_cast<double>(W.rows() - b);
  result.residual_std_dev = std::sqrt(variance);
  // Eq. 18: C = sigma^2 (W^T W)^-1 = sigma^2 P R^-1 R^-T P^T; only its diagonal is needed.
  const Eigen::MatrixXd R = qr.matrixR().topLeftCorner(b, b).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd R_inverse =
      R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(b, b));
  const Eigen::VectorXd diagonal_pivoted = R_inverse.rowwise().squaredNorm();
  result.std_dev.resize(b);
  result.rel_std_dev.resize(b);
  const auto& permutation = qr.colsPermutation().indices();
  for (Eigen::Index i = 0; i < b; ++i) {
    result.std_dev[permutation[i]] = std::sqrt(variance * diagonal_pivoted[i]);
  }
  for (Eigen::Index i = 0; i < b; ++i) {
    // Eq. 19.
    result.rel_std_dev[i] = result.value[i] != 0.0
                                ? 100.0 * result.std_dev[i] / std::abs(result.value[i])
                                : std::numeric_limits<double>::infinity();
  }
  const Eigen::VectorXd singular = Eigen::JacobiSVD<Eigen::MatrixXd>(R).singularValues();
  result.condition_number = singular[0] / singular[b - 1];
  result.relative_error_norm = y.norm() > 0 ? residual.norm() / y.norm() : residual.norm();
  return result;
}

}  // namespace

LeastSquaresResult fit_ols(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                           const std::vector<std::string>& names) {
  check_inputs(W, y, names);
  return solve(W, y, names);
}

LeastSquaresResult fit_wls(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                           const std::vector<int>& group, const std::vector<std::string>& names) {
  check_inputs(W, y, names);
  if (static_cast<Eigen::Index>(group.size()) != W.rows()) {
    throw EstimationError("one group per equation is needed: " + std::to_string(group.size()) +
                          " groups for " + std::to_string(W.rows()) + " equations");
  }
  if (*std::min_element(group.begin(), group.end()) < 0) {
    throw EstimationError("group indices must be 0 or more");
  }
  const int groups = *std::max_element(group.begin(), group.end()) + 1;
  if (groups > W.rows()) throw EstimationError("more groups than equations");
  // Eq. 20: each group's error standard deviation from the OLS solution of its own equations
  // (the block-triangular structure makes those solvable joint by joint).
  std::vector<std::vector<Eigen::Index>> rows(groups);
  for (Eigen::Index r = 0; r < W.rows(); ++r) rows[group[r]].push_back(r);
  for (int g = 0; g < groups; ++g) {
    if (rows[g].empty()) throw EstimationError("group " + std::to_string(g) + " has no equations");
  }
  std::vector<double> sigma(groups);
  for (int g = 0; g < groups; ++g) {
    const auto& members = rows[g];
    Eigen::MatrixXd Wg(members.size(), W.cols());
    Eigen::VectorXd yg(members.size());
    for (std::size_t i = 0; i < members.size(); ++i) {
      Wg.row(i) = W.row(members[i]);
      yg[i] = y[members[i]];
    }
    // Columns a group does not see (zero in its rows) are left out of its own solution.
    std::vector<Eigen::Index> seen;
    for (Eigen::Index k = 0; k < W.cols(); ++k) {
      if (Wg.col(k).cwiseAbs().maxCoeff() > 0) seen.push_back(k);
    }
    Eigen::MatrixXd Wseen(members.size(), seen.size());
    for (std::size_t k = 0; k < seen.size(); ++k) Wseen.col(k) = Wg.col(seen[k]);
    if (static_cast<Eigen::Index>(members.size()) <= Wseen.cols()) {
      throw EstimationError("group " + std::to_string(g) + " has " + std::to_string(members.size()) +
                            " equations for " + std::to_string(Wseen.cols()) +
                            " parameters: too few to estimate its error level");
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Wseen);
    const Eigen::VectorXd residual = yg - Wseen * qr.solve(yg);
    sigma[g] = std::sqrt(residual.squaredNorm() /
                         static_cast<double>(members.size() - qr.rank()));
  }
  // A group fitted exactly (noise-free data) gets the largest weight the others allow, not an
  // infinite one that would overflow the factorization.
  const double largest = *std::max_element(sigma.begin(), sigma.end());
  for (double& s : sigma) {
    if (!(s > 0)) s = largest > 0 ? 1e-6 * largest : 1.0;
  }
  Eigen::MatrixXd Ww = W;
  Eigen::VectorXd yw = y;
  for (Eigen::Index r = 0; r < W.rows(); ++r) {
    Ww.row(r) /= sigma[group[r]];
    yw[r] /= sigma[group[r]];
  }
  LeastSquaresResult result = solve(Ww, yw, names);
  result.relative_error_norm = (y - W * result.value).norm() / std::max(y.norm(), 1e-300);
  result.group_std_dev = sigma;
  return result;
}

EssentialParameters essential_parameters(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                                         const std::vector<int>& group,
                                         const std::vector<std::string>& names, double r_sigma) {
  EssentialParameters out;
  if (static_cast<Eigen::Index>(names.size()) != W.cols() || W.cols() == 0) {
    throw EstimationError("essential parameters need one name per column of a non-empty W");
  }
  for (Eigen::Index k = 0; k < W.cols(); ++k) out.kept.push_back(static_cast<int>(k));
  while (true) {
    Eigen::MatrixXd Wk(W.rows(), out.kept.size());
    std::vector<std::string> kept_names;
    for (std::size_t i = 0; i < out.kept.size(); ++i) {
      Wk.col(i) = W.col(out.kept[i]);
      kept_names.push_back(names[out.kept[i]]);
    }
    out.fit = group.empty() ? fit_ols(Wk, y, kept_names) : fit_wls(Wk, y, group, kept_names);
    Eigen::Index worst = 0;
    const double largest = out.fit.rel_std_dev.maxCoeff(&worst);
    const double smallest = out.fit.rel_std_dev.minCoeff();
    if (out.kept.size() == 1 || largest < r_sigma * smallest) return out;
    out.eliminated.push_back(out.kept[worst]);
    out.kept.erase(out.kept.begin() + worst);
  }
}

}  // namespace modelgen
