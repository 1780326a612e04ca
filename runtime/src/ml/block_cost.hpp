// The cost blocks of an MlProblem: ceres::CostFunctions over blocks of samples, with the
// analytic Jacobian (Swevers et al. 2002, eq. 18).
#pragma once

#include <ceres/cost_function.h>

#include <Eigen/Core>

#include "runtime/src/ml/problem_impl.hpp"

namespace modelgen {

// Residuals of samples [begin, end): (tau_M measured - F) / sigma on the fitted axes.
class MlProblem::Impl::BlockCost final : public ceres::CostFunction {
 public:
  BlockCost(const Impl& problem, Eigen::Index begin, Eigen::Index end)
      : problem_(problem), begin_(begin), end_(end) {
    set_num_residuals(static_cast<int>((end - begin) * problem.setup.axes.size()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(problem.unknown.size()));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const Impl& problem_;
  Eigen::Index begin_, end_;
};

}  // namespace modelgen
