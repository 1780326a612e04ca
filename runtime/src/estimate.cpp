// Least squares with the statistics of Gautier & Briot (eq. 15-20) through orthogonal
// factorizations only, never W^T W. Rows are reduced block by block per group (TSQR): the
// factor R_g of [W_g y_g] is the Householder QR of the previous factor stacked on the next
// rows, over the columns the group has seen nonzero. As [W_g y_g] = Q_g R_g with orthonormal
// Q_g, each group's own OLS (its sigma_g, eq. 20) and the weighted system (the R_g / sigma_g
// stacked) are small problems, solved by column-pivoted QR; that R gives the rank and
// (W^T W)^-1 = P R^-1 R^-T P^T (eq. 18).

#include "modelgen/estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <utility>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "runtime/src/two_parts.hpp"

namespace modelgen {

namespace {

// Rows gathered below a group's factor before a reduction: the factor's own rows (at most
// b + 1) are then a small part of each QR, and the block still fits in the core's L2 cache.
// 1024 measured fastest among 256..2048 for the TX-40 (tests/benchmarks/README.md).
constexpr Eigen::Index kBlockRows = 1024;
// A group's first block; blocks double up to kBlockRows, so small groups need little memory.
constexpr Eigen::Index kFirstBlockRows = 32;
// From this many equations on, fit_ols/fit_wls reduce the two halves of W in two threads.
constexpr Eigen::Index kParallelRows = 20000;

// One group's equations reduced so far. S has one column per position: columns[p] is the
// column of W there, or params for the right-hand side y (always position 0). Its first
// width() rows hold the factor (upper triangular), then `pending` rows not yet reduced.
struct Group {
  std::vector<int> columns;
  std::vector<int> position;       // params + 1 entries: the position of each column, or -1
  std::vector<double> column_max;  // params entries: the largest |W(i, k)| of the group
  Eigen::MatrixXd S;
  Eigen::Index pending = 0;
  Eigen::Index rows = 0;
  double y_squared = 0;

  Eigen::Index width() const { return static_cast<Eigen::Index>(columns.size()); }
  Eigen::Index capacity() const { return S.rows() - width(); }
};

// The machinery behind LeastSquaresAccumulator and fit_ols/fit_wls.
class Reducer {
 public:
  Reducer(int params, int groups) : params_(params), groups_(static_cast<std::size_t>(groups)) {
    for (Group& g : groups_) {
      g.columns = {params};
      g.position.assign(static_cast<std::size_t>(params) + 1, -1);
      g.position[static_cast<std::size_t>(params)] = 0;
      g.column_max.assign(static_cast<std::size_t>(params), 0.0);
      g.S = Eigen::MatrixXd::Zero(1, 1);
    }
  }

  int params() const { return params_; }
  int groups() const { return static_cast<int>(groups_.size()); }
  // How messages name group g: its label when the caller gave labels, else "group g".
  void set_labels(std::vector<std::string> labels) { labels_ = std::move(labels); }
  std::string label(std::size_t g) const {
    return g < labels_.size() ? labels_[g] : "group " + std::to_string(g);
  }
  const Group& group(int g) const { return groups_[static_cast<std::size_t>(g)]; }
  Eigen::Index rows() const {
    Eigen::Index total = 0;
    for (const Group& g : groups_) total += g.rows;
    return total;
  }

  // Appends `count` equations to group g, y(i) = rhs(i). Their W(i, k), k < params, are
  // row(i)[k] when `Source` is kRows (contiguous rows: the loops run along them), else
  // entry(i, k) (kColumns: the loops run along columns). `original` is false for rows of
  // another group's factor (merge): not counted as equations, no change to the statistics.
  enum Source { kRows, kColumns };
  template <Source source, class Access, class Rhs>
  void append(int g, Eigen::Index count, const Access& access, const Rhs& rhs,
              bool original = true) {
    Group& group = groups_[static_cast<std::size_t>(g)];
    for (Eigen::Index done = 0; done < count;) {
      if (group.pending == group.capacity()) {
        if (group.capacity() < kBlockRows) {
          grow(group, std::clamp(2 * group.capacity(), kFirstBlockRows, kBlockRows));
        } else {
          reduce(group);
        }
      }
      const Eigen::Index n = std::min(count - done, group.capacity() - group.pending);
      add_new_columns<source>(group, done, n, access);
      const Eigen::Index w = group.width(), ld = group.S.rows();
      double* out = &group.S(w + group.pending, 0);
      largest_.assign(static_cast<std::size_t>(w), 0.0);
      double* largest = largest_.data();
      const int* columns = group.columns.data();
      double squares = 0;
      for (Eigen::Index i = 0; i < n; ++i) {
        out[i] = rhs(done + i);
        squares += out[i] * out[i];
      }
      if constexpr (source == kRows) {
        // The column maxima came with the scan for new columns (row_max_).
        for (Eigen::Index i = 0; i < n; ++i) {
          const double* r = access(done + i);
          for (Eigen::Index p = 1; p < w; ++p) out[i + p * ld] = r[columns[p]];
        }
        for (Eigen::Index p = 1; p < w; ++p) largest[p] = row_max_[columns[p]];
      } else {
        for (Eigen::Index p = 1; p < w; ++p) {
          double* column = out + p * ld;
          for (Eigen::Index i = 0; i < n; ++i) {
            column[i] = access(done + i, columns[p]);
            largest[p] = std::max(largest[p], std::abs(column[i]));
          }
        }
      }
      if (original) {
        group.y_squared += squares;
        for (Eigen::Index p = 1; p < w; ++p) {
          double& column_max = group.column_max[static_cast<std::size_t>(columns[p])];
          column_max = std::max(column_max, largest[p]);
        }
        group.rows += n;
      }
      group.pending += n;
      done += n;
    }
  }

  // Adds the equations of `other` (same sizes): its factors' rows, which stand for them.
  void merge(Reducer&& other) {
    for (int g = 0; g < groups(); ++g) {
      Group& theirs = other.groups_[static_cast<std::size_t>(g)];
      if (theirs.rows == 0) continue;
      reduce(theirs);
      const Eigen::Index w = theirs.width();
      const auto entry = [&](Eigen::Index i, int k) {
        const int p = theirs.position[static_cast<std::size_t>(k)];
        return p < 0 ? 0.0 : theirs.S(i, p);
      };
      const auto rhs = [&](Eigen::Index i) { return theirs.S(i, 0); };
      append<kColumns>(g, w, entry, rhs, false);
      Group& ours = groups_[static_cast<std::size_t>(g)];
      ours.rows += theirs.rows;
      ours.y_squared += theirs.y_squared;
      for (int k = 0; k < params_; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        ours.column_max[kk] = std::max(ours.column_max[kk], theirs.column_max[kk]);
      }
    }
    other.groups_.clear();
  }

  // Reduces every pending row; afterwards each group's factor is S.topRows(width()).
  void reduce_all() {
    for (Group& g : groups_) reduce(g);
  }

  // reduce_all(), and the row buffers freed: only the factors stay.
  void compact() {
    for (Group& g : groups_) {
      reduce(g);
      if (g.capacity() > 0) g.S.conservativeResize(g.width(), Eigen::NoChange);
    }
  }

  // The first group whose factor holds NaN or infinity, or -1. Non-finite input always ends up
  // there: Householder reflections spread NaN and turn infinity into NaN.
  int first_non_finite() {
    reduce_all();
    for (int g = 0; g < groups(); ++g) {
      const Group& group = groups_[static_cast<std::size_t>(g)];
      if (!group.S.topRows(group.width()).allFinite()) return g;
    }
    return -1;
  }

  double residual_norm(int g, const Eigen::VectorXd& beta) {
    Group& group = groups_[static_cast<std::size_t>(g)];
    reduce(group);
    const Eigen::Index w = group.width();
    // R_g [beta; -1] has the norm of W_g beta - y_g.
    Eigen::VectorXd r = -group.S.col(0).head(w);
    for (Eigen::Index p = 1; p < w; ++p) {
      r += group.S.col(p).head(w) * beta[group.columns[static_cast<std::size_t>(p)]];
    }
    return r.norm();
  }

  LeastSquaresResult solve(const std::vector<int>& kept, const std::vector<std::string>& names,
                           bool weighted);

 private:
  // A column joins a group's factor when it is first nonzero in the group's rows; until then
  // those rows are zero there. Any set bit but the sign is nonzero: NaN counts, so that it
  // reaches the factor and is reported; -0.0 does not.
  template <Source source, class Access>
  void add_new_columns(Group& group, Eigen::Index done, Eigen::Index n, const Access& access) {
    if constexpr (source == kRows) {
      // Contiguous rows: one vectorized pass over every column, which also finds the column
      // maxima (row_max_) for the gather.
      bits_.assign(static_cast<std::size_t>(params_), 0);
      row_max_.assign(static_cast<std::size_t>(params_), 0.0);
      std::uint64_t* bits = bits_.data();
      double* largest = row_max_.data();
      for (Eigen::Index i = 0; i < n; ++i) {
        const double* r = access(done + i);
        for (int k = 0; k < params_; ++k) {
          std::uint64_t b;
          std::memcpy(&b, r + k, sizeof b);
          bits[k] |= b << 1;
          largest[k] = std::max(largest[k], std::abs(r[k]));
        }
      }
      for (int k = 0; k < params_; ++k) {
        if (bits[k] != 0 && group.position[static_cast<std::size_t>(k)] < 0) add_column(group, k);
      }
    } else {
      if (group.width() == params_ + 1) return;
      for (int k = 0; k < params_; ++k) {
        if (group.position[static_cast<std::size_t>(k)] >= 0) continue;
        for (Eigen::Index i = 0; i < n; ++i) {
          if (access(done + i, k) != 0.0) {
            add_column(group, k);
            break;
          }
        }
      }
    }
  }

  static void grow(Group& g, Eigen::Index capacity) {
    const Eigen::Index w = g.width();
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(w + capacity, w);
    S.topRows(w + g.pending) = g.S.topRows(w + g.pending);
    g.S.swap(S);
  }

  void add_column(Group& g, int k) {
    const Eigen::Index w = g.width();
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(w + 1 + g.capacity(), w + 1);
    S.topLeftCorner(w, w) = g.S.topLeftCorner(w, w);
    S.block(w + 1, 0, g.pending, w) = g.S.block(w, 0, g.pending, w);
    g.S.swap(S);
    g.position[static_cast<std::size_t>(k)] = static_cast<int>(w);
    g.columns.push_back(k);
  }

  // Householder QR in place of the factor stacked on the pending rows (Eigen's blocked
  // HouseholderQR); R replaces the factor.
  static void reduce(Group& g) {
    if (g.pending == 0) return;
    const Eigen::Index w = g.width();
    Eigen::Ref<Eigen::MatrixXd> stacked = g.S.topRows(w + g.pending);
    const Eigen::HouseholderQR<Eigen::Ref<Eigen::MatrixXd>> qr(stacked);
    g.S.topRows(w).triangularView<Eigen::StrictlyLower>().setZero();
    g.pending = 0;
  }

  int params_;
  std::vector<Group> groups_;
  std::vector<std::string> labels_;
  std::vector<std::uint64_t> bits_;  // scratch of add_new_columns()
  std::vector<double> row_max_;      // scratch of add_new_columns()
  std::vector<double> largest_;      // scratch of append()
};

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
  // slot[k]: where column k of W goes in the fit (-1: left out); the right-hand side goes last.
  std::vector<Eigen::Index> slot(static_cast<std::size_t>(params_) + 1, -1);
  for (Eigen::Index j = 0; j < b; ++j) slot[static_cast<std::size_t>(kept[j])] = j;
  slot[static_cast<std::size_t>(params_)] = b;
  const auto slot_of = [&](const Group& g, Eigen::Index p) {
    return slot[static_cast<std::size_t>(g.columns[static_cast<std::size_t>(p)])];
  };

  std::vector<double> sigma(groups_.size(), 1.0);
  if (weighted) {
    // Eq. 20: each group's error standard deviation from the OLS solution of its own equations
    // on the columns it sees, from its factor: [W_g y_g] = Q_g R_g, so the residual norms agree.
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      const Group& group = groups_[g];
      if (group.rows == 0) {
        throw EstimationError(label(g) + " has no equations");
      }
      const Eigen::Index w = group.width();
      std::vector<Eigen::Index> seen;  // positions, in the order of the fit's columns
      for (Eigen::Index p = 0; p < w; ++p) {
        const Eigen::Index j = slot_of(group, p);
        if (j >= 0 && j < b) seen.push_back(p);
      }
      std::sort(seen.begin(), seen.end(), [&](Eigen::Index x, Eigen::Index y) {
        return slot_of(group, x) < slot_of(group, y);
      });
      const Eigen::Index c = static_cast<Eigen::Index>(seen.size());
      if (group.rows <= c) {
        throw EstimationError(label(g) + " has " + std::to_string(group.rows) + " equations for " +
                              std::to_string(c) +
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
  }

  // The weighted system [W_w y_w] = blockdiag(Q_g) M, M the factors / sigma_g stacked: the same
  // least-squares problem, the same R up to signs, in sum(width) rows instead of r.
  Eigen::Index stacked_rows = 0;
  for (const Group& g : groups_) stacked_rows += g.width();
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(stacked_rows, b + 1);
  double scale = 0;  // the largest |entry| of the weighted W, for the message on rank
  Eigen::Index row = 0;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    const Group& group = groups_[g];
    const Eigen::Index w = group.width();
    for (Eigen::Index p = 0; p < w; ++p) {
      const Eigen::Index j = slot_of(group, p);
      if (j < 0) continue;
      M.block(row, j, w, 1) = group.S.col(p).head(w) / sigma[g];
      if (j < b) {
        const int k = group.columns[static_cast<std::size_t>(p)];
        scale = std::max(scale, group.column_max[static_cast<std::size_t>(k)] / sigma[g]);
      }
    }
    row += w;
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(M.leftCols(b));
  qr.setThreshold(1e-10);
  if (qr.rank() < b) {
    std::string why = unidentifiable(M.leftCols(b), scale, rows, names);
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
  for (Eigen::Index i = 0; i < b; ++i) {
    // Eq. 19.
    result.rel_std_dev[i] = result.value[i] != 0.0
                                ? 100.0 * result.std_dev[i] / std::abs(result.value[i])
                                : std::numeric_limits<double>::infinity();
  }
  // The singular values of R are those of the weighted W.
  const Eigen::VectorXd singular = Eigen::JacobiSVD<Eigen::MatrixXd>(R).singularValues();
  result.condition_number = singular[0] / singular[b - 1];
  // ||y - W value|| on the unweighted equations, group by group from the factors.
  double residual_squares = 0, y_squares = 0;
  for (const Group& group : groups_) {
    const Eigen::Index w = group.width();
    Eigen::VectorXd r = -group.S.col(0).head(w);
    for (Eigen::Index p = 1; p < w; ++p) {
      const Eigen::Index j = slot_of(group, p);
      if (j >= 0 && j < b) r += group.S.col(p).head(w) * result.value[j];
    }
    residual_squares += r.squaredNorm();
    y_squares += group.y_squared;
  }
  result.relative_error_norm =
      y_squares > 0 ? std::sqrt(residual_squares / y_squares) : std::sqrt(residual_squares);
  if (weighted) result.group_std_dev = sigma;
  return result;
}

// Where W or y holds its first non-finite value, for the message.
std::string non_finite_location(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                                const std::vector<std::string>& names) {
  const auto text = [](double v) { return std::isnan(v) ? std::string("nan") : std::to_string(v); };
  for (Eigen::Index r = 0; r < W.rows(); ++r) {
    for (Eigen::Index k = 0; k < W.cols(); ++k) {
      if (!std::isfinite(W(r, k))) {
        return "W row " + std::to_string(r + 1) + ", column '" +
               names[static_cast<std::size_t>(k)] + "' is " + text(W(r, k));
      }
    }
    if (!std::isfinite(y[r])) return "Y row " + std::to_string(r + 1) + " is " + text(y[r]);
  }
  return "values overflow during the factorization (entries too large for double precision)";
}

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
  if (W.cols() == 0) throw EstimationError("W has no columns: there is nothing to estimate");
  if (W.rows() <= W.cols()) {
    throw EstimationError("only " + std::to_string(W.rows()) + " equations for " +
                          std::to_string(W.cols()) + " parameters: more data are needed");
  }
}

// The number of groups of a valid `group` vector for W (one entry per row, 0..G-1, none empty).
int check_groups(const Eigen::MatrixXd& W, const std::vector<int>& group) {
  if (static_cast<Eigen::Index>(group.size()) != W.rows()) {
    throw EstimationError("one group per equation is needed: " + std::to_string(group.size()) +
                          " groups for " + std::to_string(W.rows()) + " equations");
  }
  if (*std::min_element(group.begin(), group.end()) < 0) {
    throw EstimationError("group indices must be 0 or more");
  }
  const int groups = *std::max_element(group.begin(), group.end()) + 1;
  if (groups > W.rows()) throw EstimationError("more groups than equations");
  std::vector<char> used(static_cast<std::size_t>(groups), 0);
  for (int g : group) used[static_cast<std::size_t>(g)] = 1;
  for (int g = 0; g < groups; ++g) {
    if (!used[static_cast<std::size_t>(g)]) {
      throw EstimationError("group " + std::to_string(g) + " has no equations");
    }
  }
  return groups;
}

// W's rows reduced per group (one group if `group` is empty), the two halves of the rows in
// two threads for a large W. Checks everything fit_ols/fit_wls promise to check.
Reducer reduce_matrix(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                      const std::vector<int>& group, const std::vector<std::string>& names) {
  check_inputs(W, y, names);
  const int groups = group.empty() ? 1 : check_groups(W, group);
  const int b = static_cast<int>(W.cols());
  Reducer parts[2] = {Reducer(b, groups), Reducer(b, groups)};
  const Eigen::Index half = W.rows() / 2;
  internal::run_two_parts(
      W.rows() >= kParallelRows,
      [&](int part, bool) {
        const Eigen::Index begin = part == 0 ? 0 : half, end = part == 0 ? half : W.rows();
        Reducer& reducer = parts[part];
        // Blocks of consecutive rows copied row-major (one read of W from memory, contiguous rows
        // for the reducer's vectorized pass), then handed over group by group.
        using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        RowMajor block(std::min(kBlockRows, end - begin), W.cols());
        std::vector<std::vector<Eigen::Index>> members(static_cast<std::size_t>(groups));
        for (Eigen::Index start = begin; start < end; start += kBlockRows) {
          const Eigen::Index count = std::min(end, start + kBlockRows) - start;
          block.topRows(count) = W.middleRows(start, count);
          for (auto& m : members) m.clear();
          for (Eigen::Index r = start; r < start + count; ++r) {
            const int g = group.empty() ? 0 : group[static_cast<std::size_t>(r)];
            members[static_cast<std::size_t>(g)].push_back(r);
          }
          for (int g = 0; g < groups; ++g) {
            const std::vector<Eigen::Index>& m = members[static_cast<std::size_t>(g)];
            if (m.empty()) continue;
            reducer.append<Reducer::kRows>(
                g, static_cast<Eigen::Index>(m.size()),
                [&](Eigen::Index i) { return &block(m[static_cast<std::size_t>(i)] - start, 0); },
                [&](Eigen::Index i) { return y[m[static_cast<std::size_t>(i)]]; });
          }
        }
      },
      [] {});
  parts[0].merge(std::move(parts[1]));
  if (parts[0].first_non_finite() >= 0) {
    throw EstimationError("W or Y holds NaN or infinite values: " +
                          non_finite_location(W, y, names));
  }
  return std::move(parts[0]);
}

std::vector<int> all_columns(int b) {
  std::vector<int> kept(static_cast<std::size_t>(b));
  for (int k = 0; k < b; ++k) kept[static_cast<std::size_t>(k)] = k;
  return kept;
}

// Pham & Gautier's elimination; fit(kept, kept_names) fits on a subset of the columns.
template <class Fit>
EssentialParameters eliminate(int params, const Fit& fit, const std::vector<std::string>& names,
                              double r_sigma) {
  if (!(r_sigma > 1) || !std::isfinite(r_sigma)) {
    throw EstimationError("r_sigma must be a finite ratio above 1 (Gautier & Briot use 20), not " +
                          std::to_string(r_sigma));
  }
  EssentialParameters out;
  out.kept = all_columns(params);
  while (true) {
    std::vector<std::string> kept_names;
    for (int k : out.kept) kept_names.push_back(names[static_cast<std::size_t>(k)]);
    out.fit = fit(out.kept, kept_names);
    Eigen::Index worst = 0;
    const double largest = out.fit.rel_std_dev.maxCoeff(&worst);
    const double smallest = out.fit.rel_std_dev.minCoeff();
    // <= so that exact data (every %std 0) keep every parameter: nothing is less certain.
    if (out.kept.size() == 1 || largest <= r_sigma * smallest) return out;
    out.eliminated.push_back(out.kept[static_cast<std::size_t>(worst)]);
    out.kept.erase(out.kept.begin() + worst);
  }
}

}  // namespace

struct LeastSquaresAccumulator::Impl {
  Reducer reducer;
};

LeastSquaresAccumulator::LeastSquaresAccumulator(int params, int groups) {
  if (params < 1 || groups < 1) {
    throw EstimationError(
        "a least-squares accumulator needs at least one parameter and one group, "
        "got " +
        std::to_string(params) + " and " + std::to_string(groups));
  }
  impl_ = std::make_unique<Impl>(Impl{Reducer(params, groups)});
}

LeastSquaresAccumulator::~LeastSquaresAccumulator() = default;
LeastSquaresAccumulator::LeastSquaresAccumulator(LeastSquaresAccumulator&&) noexcept = default;
LeastSquaresAccumulator& LeastSquaresAccumulator::operator=(LeastSquaresAccumulator&&) noexcept =
    default;

void LeastSquaresAccumulator::name_groups(std::vector<std::string> labels) {
  impl_->reducer.set_labels(std::move(labels));
}

int LeastSquaresAccumulator::params() const { return impl_->reducer.params(); }
int LeastSquaresAccumulator::groups() const { return impl_->reducer.groups(); }
Eigen::Index LeastSquaresAccumulator::rows() const { return impl_->reducer.rows(); }

Eigen::Index LeastSquaresAccumulator::rows(int group) const {
  if (group < 0 || group >= groups()) {
    throw EstimationError("group " + std::to_string(group) + " out of range 0.." +
                          std::to_string(groups() - 1));
  }
  return impl_->reducer.group(group).rows;
}

void LeastSquaresAccumulator::add(int group, Eigen::Index count, const double* W,
                                  Eigen::Index row_stride, Eigen::Index col_stride, const double* y,
                                  Eigen::Index y_stride) {
  if (group < 0 || group >= groups()) {
    throw EstimationError("group " + std::to_string(group) + " out of range 0.." +
                          std::to_string(groups() - 1));
  }
  if (count < 0) throw EstimationError("a negative number of equations was added");
  const auto rhs = [&](Eigen::Index i) { return y[i * y_stride]; };
  // Along rows when they are contiguous in memory (a row-major block), else along columns.
  if (col_stride == 1 && row_stride != 1) {
    impl_->reducer.append<Reducer::kRows>(
        group, count, [&](Eigen::Index i) { return W + i * row_stride; }, rhs);
  } else {
    impl_->reducer.append<Reducer::kColumns>(
        group, count, [&](Eigen::Index i, int k) { return W[i * row_stride + k * col_stride]; },
        rhs);
  }
}

void LeastSquaresAccumulator::compact() { impl_->reducer.compact(); }

void LeastSquaresAccumulator::merge(LeastSquaresAccumulator&& other) {
  if (other.params() != params() || other.groups() != groups()) {
    throw EstimationError(
        "cannot merge equations of different sizes: " + std::to_string(other.params()) +
        " parameters in " + std::to_string(other.groups()) + " groups into " +
        std::to_string(params()) + " in " + std::to_string(groups()));
  }
  impl_->reducer.merge(std::move(other.impl_->reducer));
  other.impl_ = std::make_unique<Impl>(Impl{Reducer(params(), groups())});
}

double LeastSquaresAccumulator::y_norm(int group) const {
  rows(group);  // checks the range
  return std::sqrt(impl_->reducer.group(group).y_squared);
}

double LeastSquaresAccumulator::residual_norm(int group, const Eigen::VectorXd& beta) const {
  rows(group);  // checks the range
  if (beta.size() != params()) {
    throw EstimationError("beta has " + std::to_string(beta.size()) + " entries for " +
                          std::to_string(params()) + " parameters");
  }
  return impl_->reducer.residual_norm(group, beta);
}

LeastSquaresResult LeastSquaresAccumulator::fit(const std::vector<int>& kept,
                                                const std::vector<std::string>& kept_names,
                                                bool weighted) const {
  if (kept_names.size() != kept.size()) {
    throw EstimationError("W has " + std::to_string(kept.size()) + " columns but " +
                          std::to_string(kept_names.size()) + " parameter names were given");
  }
  if (kept.empty()) throw EstimationError("a fit needs at least one column");
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (kept[i] < 0 || kept[i] >= params() || (i > 0 && kept[i] <= kept[i - 1])) {
      throw EstimationError("kept columns must be ascending indices below " +
                            std::to_string(params()));
    }
  }
  return impl_->reducer.solve(kept, kept_names, weighted);
}

LeastSquaresResult LeastSquaresAccumulator::fit_ols(const std::vector<std::string>& names) const {
  return fit(all_columns(params()), names, false);
}

LeastSquaresResult LeastSquaresAccumulator::fit_wls(const std::vector<std::string>& names) const {
  return fit(all_columns(params()), names, true);
}

LeastSquaresResult fit_ols(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                           const std::vector<std::string>& names) {
  Reducer reducer = reduce_matrix(W, y, {}, names);
  return reducer.solve(all_columns(static_cast<int>(W.cols())), names, false);
}

LeastSquaresResult fit_wls(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                           const std::vector<int>& group, const std::vector<std::string>& names) {
  if (group.empty() && W.rows() > 0) {
    throw EstimationError("one group per equation is needed: 0 groups for " +
                          std::to_string(W.rows()) + " equations");
  }
  Reducer reducer = reduce_matrix(W, y, group, names);
  return reducer.solve(all_columns(static_cast<int>(W.cols())), names, true);
}

EssentialParameters essential_parameters(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                                         const std::vector<int>& group,
                                         const std::vector<std::string>& names, double r_sigma) {
  if (static_cast<Eigen::Index>(names.size()) != W.cols() || W.cols() == 0) {
    throw EstimationError("essential parameters need one name per column of a non-empty W");
  }
  Reducer reducer = reduce_matrix(W, y, group, names);
  const bool weighted = !group.empty();
  return eliminate(
      reducer.params(),
      [&](const std::vector<int>& kept, const std::vector<std::string>& kept_names) {
        return reducer.solve(kept, kept_names, weighted);
      },
      names, r_sigma);
}

EssentialParameters essential_parameters(const LeastSquaresAccumulator& equations, bool weighted,
                                         const std::vector<std::string>& names, double r_sigma) {
  if (static_cast<int>(names.size()) != equations.params()) {
    throw EstimationError(
        "essential parameters need one name per column: " + std::to_string(names.size()) +
        " names for " + std::to_string(equations.params()) + " columns");
  }
  return eliminate(
      equations.params(),
      [&](const std::vector<int>& kept, const std::vector<std::string>& kept_names) {
        return equations.fit(kept, kept_names, weighted);
      },
      names, r_sigma);
}

}  // namespace modelgen
