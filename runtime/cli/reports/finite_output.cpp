// The finite-output checks of predict and simulate.

#include "runtime/cli/reports/finite_output.hpp"

#include <cmath>
#include <cstddef>

#include "modelgen/model/number_text.hpp"

namespace modelgen::internal {

std::string first_non_finite(const Eigen::MatrixXd& values, const Eigen::VectorXd& t,
                             const std::string& column) {
  for (Eigen::Index s = 0; s < values.rows(); ++s) {
    for (Eigen::Index j = 0; j < values.cols(); ++j) {
      if (std::isfinite(values(s, j))) continue;
      return column + std::to_string(j + 1) + " is " + shortest_text(values(s, j)) +
             " at t = " + shortest_text(t[s]) + " s";
    }
  }
  return "";
}

std::string largest_parameter(const Eigen::VectorXd& values, const std::vector<std::string>& names,
                              const std::string& kind) {
  if (values.size() == 0) return "";
  Eigen::Index largest = 0;
  values.cwiseAbs().maxCoeff(&largest);
  return " (the largest " + kind + " is '" + names[static_cast<std::size_t>(largest)] +
         "' = " + shortest_text(values[largest]) + ")";
}

}  // namespace modelgen::internal
