// Least squares through orthogonal factorizations only, never W^T W. Rows are reduced block by
// block per group (TSQR): the factor R_g of [W_g y_g] is the Householder QR of the previous
// factor stacked on the next rows (fold_rows), over the columns the group has seen nonzero.
// The Reducer holds the factors; LeastSquaresAccumulator, fit_ols, fit_wls and
// essential_parameters work through it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "modelgen/estimation/least_squares.hpp"

namespace modelgen::detail {

// Rows gathered below a group's factor before a reduction (fold_rows, which does not touch the
// factor's zeros, so blocks need not be tall). For the TX-40 (tests/benchmarks/README.md) 256
// and 512 measured alike, 128 and 1024 slower; at 256 a buffer of (b + 257) x (b + 1) doubles
// stays under malloc's mmap threshold, so it is reused rather than mapped anew per call.
constexpr Eigen::Index kBlockRows = 256;
// A group's first block; blocks double up to kBlockRows, so small groups need little memory.
constexpr Eigen::Index kFirstBlockRows = 32;

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
        // Column by column into contiguous stores (the rows' lines stay cached across
        // neighbouring columns), then each column's maximum over the copy.
        rows_.resize(static_cast<std::size_t>(n));
        for (Eigen::Index i = 0; i < n; ++i) rows_[static_cast<std::size_t>(i)] = access(done + i);
        const double* const* rows = rows_.data();
        for (Eigen::Index p = 1; p < w; ++p) {
          double* column = out + p * ld;
          const int k = columns[p];
          for (Eigen::Index i = 0; i < n; ++i) column[i] = rows[i][k];
          largest[p] = largest_magnitude(column, n);
        }
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
  void merge(Reducer&& other);

  // Reduces every pending row; afterwards each group's factor is S.topRows(width()).
  void reduce_all();

  // reduce_all(), and the row buffers freed: only the factors stay.
  void compact();

  // The first group whose factor holds NaN or infinity, or -1. Non-finite input always ends up
  // there: Householder reflections spread NaN and turn infinity into NaN.
  int first_non_finite();

  // ||y_g - W_g beta|| of group g's equations, from its factor.
  double residual_norm(int g, const Eigen::VectorXd& beta);

  // The fit on the columns `kept` (ascending; `names` theirs, for messages), WLS over the
  // groups when `weighted`, with every statistic of LeastSquaresResult (fit_statistics.cpp).
  // Throws EstimationError for too few equations, non-finite values, a rank-deficient W.
  LeastSquaresResult solve(const std::vector<int>& kept, const std::vector<std::string>& names,
                           bool weighted);

 private:
  // A column joins a group's factor when it is first nonzero in the group's rows; until then
  // those rows are zero there. NaN counts (it compares unequal to 0), so that it reaches the
  // factor and is reported; -0.0 does not. Only the columns not yet in the factor are
  // examined: contiguous rows first in one pass that ORs their bits (any bit but the sign set
  // means some nonzero), then, only if so, column by column up to the first nonzero.
  template <Source source, class Access>
  void add_new_columns(Group& group, Eigen::Index done, Eigen::Index n, const Access& access) {
    if (group.width() == params_ + 1) return;
    if constexpr (source == kRows) {
      absent_.clear();
      for (int k = 0; k < params_; ++k) {
        if (group.position[static_cast<std::size_t>(k)] < 0) absent_.push_back(k);
      }
      std::uint64_t bits = 0;
      for (Eigen::Index i = 0; i < n; ++i) {
        const double* r = access(done + i);
        for (const int k : absent_) {
          std::uint64_t b;
          std::memcpy(&b, r + k, sizeof b);
          bits |= b;
        }
      }
      if ((bits << 1) == 0) return;
    }
    for (int k = 0; k < params_; ++k) {
      if (group.position[static_cast<std::size_t>(k)] >= 0) continue;
      for (Eigen::Index i = 0; i < n; ++i) {
        double entry;
        if constexpr (source == kRows) {
          entry = access(done + i)[k];
        } else {
          entry = access(done + i, k);
        }
        if (entry != 0.0) {
          add_column(group, k);
          break;
        }
      }
    }
  }

  // max |x_i| over n contiguous entries (NaN skipped, as std::max does).
  static double largest_magnitude(const double* x, Eigen::Index n) {
    double m0 = 0, m1 = 0, m2 = 0, m3 = 0;
    Eigen::Index i = 0;
    for (; i + 4 <= n; i += 4) {
      m0 = std::max(m0, std::abs(x[i]));
      m1 = std::max(m1, std::abs(x[i + 1]));
      m2 = std::max(m2, std::abs(x[i + 2]));
      m3 = std::max(m3, std::abs(x[i + 3]));
    }
    for (; i < n; ++i) m0 = std::max(m0, std::abs(x[i]));
    return std::max(std::max(m0, m1), std::max(m2, m3));
  }

  // A row buffer of `capacity` rows below the factor, pending rows kept.
  static void grow(Group& g, Eigen::Index capacity);

  // Column k of W joins the group's factor (zero in the rows so far).
  void add_column(Group& g, int k);

  // Householder QR of the factor stacked on the pending rows (fold_rows, structured: the
  // factor's zeros cost nothing); R replaces the factor, the pending rows are scratch.
  static void reduce(Group& g);

  int params_;
  std::vector<Group> groups_;
  std::vector<std::string> labels_;
  std::vector<double> largest_;      // scratch of append()
  std::vector<int> absent_;          // scratch of add_new_columns()
  std::vector<const double*> rows_;  // scratch of append()
};

/// Every column index 0..b-1, ascending: a fit on all columns.
std::vector<int> all_columns(int b);

/// W's rows reduced per group (one group if `group` is empty), the two halves of the rows in
/// two threads for a large W. Checks everything fit_ols/fit_wls promise to check (sizes, groups,
/// non-finite values named by row and column) and throws EstimationError.
Reducer reduce_matrix(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                      const std::vector<int>& group, const std::vector<std::string>& names);

}  // namespace modelgen::detail
