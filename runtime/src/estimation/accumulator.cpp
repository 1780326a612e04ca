// LeastSquaresAccumulator: the public face of one Reducer.

#include "modelgen/estimation/accumulator.hpp"

#include <cmath>
#include <memory>
#include <utility>

#include "runtime/src/estimation/reducer.hpp"

namespace modelgen {

using detail::all_columns;
using detail::Reducer;

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

}  // namespace modelgen
