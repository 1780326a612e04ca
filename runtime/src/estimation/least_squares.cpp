// fit_ols and fit_wls on a whole W: its rows reduced to the Reducer's factors (in two threads
// for a large W), then solved from them (fit_statistics.cpp).

#include "modelgen/estimation/least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "runtime/src/estimation/reducer.hpp"
#include "runtime/src/estimation/two_parts.hpp"

namespace modelgen {

namespace detail {

namespace {

// From this many equations on, fit_ols/fit_wls reduce the two halves of W in two threads.
constexpr Eigen::Index kParallelRows = 20000;

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

}  // namespace

// W's rows reduced per group (one group if `group` is empty), the two halves of the rows in
// two threads for a large W. Checks everything fit_ols/fit_wls promise to check.
Reducer reduce_matrix(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                      const std::vector<int>& group, const std::vector<std::string>& names) {
  check_inputs(W, y, names);
  const int groups = group.empty() ? 1 : check_groups(W, group);
  const int b = static_cast<int>(W.cols());
  Reducer parts[2] = {Reducer(b, groups), Reducer(b, groups)};
  const Eigen::Index half = W.rows() / 2;
  detail::run_two_parts(
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

}  // namespace detail

using detail::all_columns;
using detail::reduce_matrix;
using detail::Reducer;

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

}  // namespace modelgen
