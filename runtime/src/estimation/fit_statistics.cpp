// The fit and its statistics from the Reducer's factors (Gautier & Briot eq. 15-20): as
// [W_g y_g] = Q_g R_g with orthonormal Q_g, each group's own OLS (its sigma_g, eq. 20) and the
// weighted system (the R_g / sigma_g stacked) are small problems, solved by column-pivoted QR;
// that R gives the rank and (W^T W)^-1 = P R^-1 R^-T P^T (eq. 18).

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "runtime/src/estimation/reducer.hpp"

namespace modelgen::detail {

namespace {

// Names of the columns of A that are zero or combinations of earlier ones (in column order),
// for the message of a rank-deficient W. A is W or any matrix with the same A^T A (a stack of
// factors); `scale` is the largest |W| entry and `rows` the number of rows of W, which set the
// threshold of a zero column as if W itself were examined.
std::string unidentifiable(const Eigen::MatrixXd& A, double scale, Eigen::Index rows,
                           const std::vector<std::string>& names) {
  Eigen::MatrixXd Q(A.rows(), 0);
  std::ostringstream zero, dependent;
  for (Eigen::Index k = 0; k < A.cols(); ++k) {
    Eigen::VectorXd v = A.col(k);
    const double norm = v.norm();
    if (norm <= 1e-12 * scale * std::sqrt(static_cast<double>(rows))) {
      zero << " " << names[static_cast<std::size_t>(k)];
      continue;
    }
    for (int pass = 0; pass < 2; ++pass) v -= Q * (Q.transpose() * v);
    // Looser than the QR rank threshold, so that nearly dependent columns are named too.
    if (v.norm() <= 1e-7 * norm) {
      dependent << " " << names[static_cast<std::size_t>(k)];
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

// slot[k]: where column k of W goes in the fit (-1: left out); the right-hand side goes last.
class Slots {
 public:
  Slots(const std::vector<int>& kept, int params)
      : slot_(static_cast<std::size_t>(params) + 1, -1) {
    const Eigen::Index b = static_cast<Eigen::Index>(kept.size());
    for (Eigen::Index j = 0; j < b; ++j) slot_[static_cast<std::size_t>(kept[j])] = j;
    slot_[static_cast<std::size_t>(params)] = b;
  }
  // The slot of the group's column at position p.
  Eigen::Index of(const Group& g, Eigen::Index p) const {
    return slot_[static_cast<std::size_t>(g.columns[static_cast<std::size_t>(p)])];
  }

 private:
  std::vector<Eigen::Index> slot_;
};

// Eq. 20: each group's error standard deviation from the OLS solution of its own equations
// on the columns it sees, from its factor: [W_g y_g] = Q_g R_g, so the residual norms agree.
std::vector<double> group_sigmas(const Reducer& reducer, const Slots& slots, Eigen::Index b) {
  std::vector<double> sigma(static_cast<std::size_t>(reducer.groups()), 1.0);
  for (std::size_t g = 0; g < sigma.size(); ++g) {
    const Group& group = reducer.group(static_cast<int>(g));
    if (group.rows == 0) {
      throw EstimationError(reducer.label(g) + " has no equations");
    }
    const Eigen::Index w = group.width();
    std::vector<Eigen::Index> seen;  // positions, in the order of the fit's columns
    for (Eigen::Index p = 0; p < w; ++p) {
      const Eigen::Index j = slots.of(group, p);
      if (j >= 0 && j < b) seen.push_back(p);
    }
    std::sort(seen.begin(), seen.end(), [&](Eigen::Index x, Eigen::Index y) {
      return slots.of(group, x) < slots.of(group, y);
    });
    const Eigen::Index c = static_cast<Eigen::Index>(seen.size());
    if (group.rows <= c) {
      throw EstimationError(reducer.label(g) + " has " + std::to_string(group.rows) +
                            " equations for " + std::to_string(c) +
                            " parameters: too few to estimate its error level");
    }
    const auto R = group.S.topRows(w);
    const Eigen::VectorXd r = R.col(0);
    double squares = r.squaredNorm();
    Eigen::Index rank = 0;
    if (c > 0) {
      Eigen::MatrixXd A(w, c);
      for (Eigen::Index j = 0; j < c; ++j) A.col(j) = R.col(seen[static_cast<std::size_t>(j)]);
      const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
      squares = (r - A * qr.solve(r)).squaredNorm();
      rank = qr.rank();
    }
    sigma[g] = std::sqrt(squares / static_cast<double>(group.rows - rank));
  }
  // A group fitted exactly (noise-free data) gets the largest weight the others allow, not
  // an infinite one that would overflow the factorization.
  const double largest = *std::max_element(sigma.begin(), sigma.end());
  for (double& s : sigma) {
    if (!(s > 0)) s = largest > 0 ? 1e-6 * largest : 1.0;
  }
  return sigma;
}

// The weighted system's factors M, and the largest |entry| of the weighted W (for the message
// on rank).
struct WeightedFactors {
  Eigen::MatrixXd M;
  double scale = 0;
};

// The weighted system [W_w y_w] = blockdiag(Q_g) M, M the factors / sigma_g stacked: the same
// least-squares problem, the same R up to signs, in sum(width) rows instead of r.
WeightedFactors weighted_factors(const Reducer& reducer, const Slots& slots,
                                 const std::vector<double>& sigma, Eigen::Index b) {
  Eigen::Index stacked_rows = 0;
  for (int g = 0; g < reducer.groups(); ++g) stacked_rows += reducer.group(g).width();
  WeightedFactors factors;
  Eigen::MatrixXd& M = factors.M;
  M = Eigen::MatrixXd::Zero(stacked_rows, b + 1);
  Eigen::Index row = 0;
  for (std::size_t g = 0; g < sigma.size(); ++g) {
    const Group& group = reducer.group(static_cast<int>(g));
    const Eigen::Index w = group.width();
    for (Eigen::Index p = 0; p < w; ++p) {
      const Eigen::Index j = slots.of(group, p);
      if (j < 0) continue;
      M.block(row, j, w, 1) = group.S.col(p).head(w) / sigma[g];
      if (j < b) {
        const int k = group.columns[static_cast<std::size_t>(p)];
        factors.scale =
            std::max(factors.scale, group.column_max[static_cast<std::size_t>(k)] / sigma[g]);
      }
    }
    row += w;
  }
  return factors;
}

// The error for a rank-deficient W, naming the columns that make it so.
[[noreturn]] void throw_rank_deficient(const Eigen::ColPivHouseholderQR<Eigen::MatrixXd>& qr,
                                       const WeightedFactors& factors, Eigen::Index rows,
                                       const std::vector<std::string>& names, Eigen::Index b) {
  std::string why = unidentifiable(factors.M.leftCols(b), factors.scale, rows, names);
  if (why.empty()) {
    // Dependent only at the scale of the whole matrix (e.g. WLS weights of very different
    // sizes): name the columns the pivoting QR left last, those it could not resolve.
    why =
        " too weakly determined next to the others (the data or the weights make them "
        "negligible):";
    const auto& order = qr.colsPermutation().indices();
    for (Eigen::Index i = qr.rank(); i < b; ++i) {
      why += " " + names[static_cast<std::size_t>(order[i])];
    }
    why += ".";
  }
  throw EstimationError("W is rank-deficient (rank " + std::to_string(qr.rank()) + " of " +
                        std::to_string(b) + "):" + why);
}

// The estimate and its statistics (eq. 17-19) from the QR of the weighted system.
LeastSquaresResult estimate(const Eigen::ColPivHouseholderQR<Eigen::MatrixXd>& qr,
                            const Eigen::MatrixXd& M, Eigen::Index rows, Eigen::Index b) {
  LeastSquaresResult result;
  result.value = qr.solve(M.col(b));
  // Eq. 17: unbiased estimate of the (weighted) equation error's variance.
  const double variance =
      (M.col(b) - M.leftCols(b) * result.value).squaredNorm() / static_cast<double>(rows - b);
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
  // W'W = P R'R P' (the same QR), over the variance.
  const Eigen::MatrixXd RP = R * qr.colsPermutation().transpose();
  result.information = RP.transpose() * RP / variance;
  result.equations = static_cast<long long>(rows);
  for (Eigen::Index i = 0; i < b; ++i) {
    // Eq. 19.
    result.rel_std_dev[i] = result.value[i] != 0.0
                                ? 100.0 * result.std_dev[i] / std::abs(result.value[i])
                                : std::numeric_limits<double>::infinity();
  }
  // The singular values of R are those of the weighted W.
  const Eigen::VectorXd singular = Eigen::JacobiSVD<Eigen::MatrixXd>(R).singularValues();
  result.condition_number = singular[0] / singular[b - 1];
  return result;
}

// ||y - W value|| / ||y|| on the unweighted equations, group by group from the factors.
double relative_error_norm(const Reducer& reducer, const Slots& slots, const Eigen::VectorXd& value,
                           Eigen::Index b) {
  double residual_squares = 0, y_squares = 0;
  for (int g = 0; g < reducer.groups(); ++g) {
    const Group& group = reducer.group(g);
    const Eigen::Index w = group.width();
    Eigen::VectorXd r = -group.S.col(0).head(w);
    for (Eigen::Index p = 1; p < w; ++p) {
      const Eigen::Index j = slots.of(group, p);
      if (j >= 0 && j < b) r += group.S.col(p).head(w) * value[j];
    }
    residual_squares += r.squaredNorm();
    y_squares += group.y_squared;
  }
  return y_squares > 0 ? std::sqrt(residual_squares / y_squares) : std::sqrt(residual_squares);
}

}  // namespace

LeastSquaresResult Reducer::solve(const std::vector<int>& kept,
                                  const std::vector<std::string>& names, bool weighted) {
  const Eigen::Index b = static_cast<Eigen::Index>(kept.size());
  const Eigen::Index rows = this->rows();
  if (rows <= b) {
    throw EstimationError("only " + std::to_string(rows) + " equations for " + std::to_string(b) +
                          " parameters: more data are needed");
  }
  const int bad = first_non_finite();
  if (bad >= 0) {
    throw EstimationError("W or Y holds NaN or infinite values (in " +
                          label(static_cast<std::size_t>(bad)) + ")");
  }
  const Slots slots(kept, params_);
  const std::vector<double> sigma =
      weighted ? group_sigmas(*this, slots, b) : std::vector<double>(groups_.size(), 1.0);
  const WeightedFactors factors = weighted_factors(*this, slots, sigma, b);
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(factors.M.leftCols(b));
  qr.setThreshold(1e-10);
  if (qr.rank() < b) throw_rank_deficient(qr, factors, rows, names, b);
  LeastSquaresResult result = estimate(qr, factors.M, rows, b);
  result.relative_error_norm = relative_error_norm(*this, slots, result.value, b);
  if (weighted) result.group_std_dev = sigma;
  return result;
}

}  // namespace modelgen::detail
