// Standard deviations of least-squares estimates from the weighted Jacobian at the optimum,
// shared by the maximum-likelihood fits (fit.cpp, physical_fit.cpp).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace modelgen::detail {

/// sqrt of the diagonal of s2 (J^T J)^-1 over the columns of J marked in `keep` (the others, and
/// columns held at a bound, get NaN), computed on unit-norm columns by the SVD.
Eigen::VectorXd standard_deviations(const Eigen::MatrixXd& J, const std::vector<bool>& keep,
                                    double s2);

}  // namespace modelgen::detail
