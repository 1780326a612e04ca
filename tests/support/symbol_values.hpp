// Numeric values for the leaves of the generator's symbolic expressions, so generator tests can
// evaluate an expression at a state and compare it with the numeric reference.
#pragma once

#include <functional>

#include <Eigen/Core>

#include "generator/symbolic/expr.hpp"

namespace modelgen::test {

/// Values of the leaves of the symbolic models at a state: inputs by their C++ text (q[i],
/// dq[i], ddq[i], p[k]), derived leaves (sin, cos, sign, ...) from their input. The vectors are
/// captured by reference.
std::function<double(const gen::Symbol&)> symbol_values(const Eigen::VectorXd& q,
                                                        const Eigen::VectorXd& dq,
                                                        const Eigen::VectorXd& ddq,
                                                        const Eigen::VectorXd& p);

}  // namespace modelgen::test
