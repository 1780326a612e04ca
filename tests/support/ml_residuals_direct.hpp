// The weighted residuals of Swevers et al. 2002, eq. 18, written directly for any scalar type
// through the templated reference drive model and standard_from_load (eq. 3), nothing of
// MlProblem's chain rule: with T = ceres::Jet they give the Jacobian by automatic
// differentiation (the oracle of tests/runtime/ml/ml_fit_test.cpp, the autodiff variant of
// tests/benchmarks/ml_benchmark.cpp).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "modelgen/ml/drive_model.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/ml/problem.hpp"

namespace modelgen::test {

/// The residuals (measured - F) / sigma of `problem`'s samples [begin, end) at the unknowns
/// `theta1` (problem.num_unknowns() values), axis fastest as in MlProblem::evaluate: that is
/// (end - begin) * problem.axes().size() values into `residuals`. `model` must be the reference
/// drive model `problem` was built on (its samples bound by the problem).
template <class T>
void direct_ml_residuals(const MlProblem& problem, const ReferenceDriveModel& model,
                         const T* theta1, Eigen::Index begin, Eigen::Index end, T* residuals) {
  const int P = model.num_params();
  const Eigen::VectorXd& values = problem.values();
  std::vector<T> all(static_cast<size_t>(values.size()));
  for (Eigen::Index k = 0; k < values.size(); ++k) all[k] = T(values[k]);
  for (int u = 0; u < problem.num_unknowns(); ++u) all[problem.unknown_indices()[u]] = theta1[u];
  std::vector<T> theta(all.begin(), all.begin() + P);
  if (!problem.payload_indices().empty()) {
    T load_standard[10];
    standard_from_load(all.data() + P, load_standard);
    for (int m = 0; m < 10; ++m) theta[problem.payload_indices()[m]] += load_standard[m];
  }
  std::vector<T> tau(static_cast<size_t>(model.dof()));
  for (Eigen::Index s = begin; s < end; ++s) {
    model.evaluate(s, theta.data(), tau.data());
    for (const int i : problem.axes()) {
      *residuals++ = (problem.measured()(s, i) - tau[i]) / problem.sigma()(s, i);
    }
  }
}

}  // namespace modelgen::test
