// What an MlProblem holds, for the library's own files: the bound drive model, the unknowns,
// the stacked measurements and the cost blocks (Ceres cost functions, block_cost.hpp).
#pragma once

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/ml/problem.hpp"

namespace ceres {
class CostFunction;
}  // namespace ceres

namespace modelgen {

struct MlProblem::Impl {
  class BlockCost;

  DriveModel* model = nullptr;
  MlSetup setup;
  std::vector<std::string> names;  // ml_param_names
  std::vector<int> unknown;        // indices into names
  std::vector<int> payload;        // drive-parameter indices of XXj .. Mj
  int P = 0;                       // drive model parameters
  Eigen::VectorXd values;
  Eigen::MatrixXd measured, sigma;  // stacked samples x dof
  std::vector<std::unique_ptr<BlockCost>> blocks;
  Eigen::Index residuals = 0;

  bool unknown_load() const {
    return std::any_of(unknown.begin(), unknown.end(), [&](int k) { return k >= P; });
  }

  Eigen::VectorXd drive_parameters(const Eigen::VectorXd& all) const {
    Eigen::VectorXd theta = all.head(P);
    if (!payload.empty()) {
      double standard[10];
      standard_from_load(all.data() + P, standard);
      for (int m = 0; m < 10; ++m) theta[payload[m]] += standard[m];
    }
    return theta;
  }

  Eigen::VectorXd with_unknowns(const double* theta1) const {
    Eigen::VectorXd all = values;
    for (size_t u = 0; u < unknown.size(); ++u) all[unknown[u]] = theta1[u];
    return all;
  }
};

namespace detail {

/// The library's access to an MlProblem's insides.
class MlProblemAccess {
 public:
  /// The cost functions (owned by `problem`) whose residuals stack to MlProblem::evaluate()'s,
  /// each with one parameter block: theta1, num_unknowns() values.
  static std::vector<ceres::CostFunction*> cost_functions(const MlProblem& problem);
};

}  // namespace detail

}  // namespace modelgen
