// The errors-in-variables library's access to ErrorsInVariablesObjective's insides
// (errors_in_variables.cpp, errors_in_variables_score.cpp).
#pragma once

#include <optional>

#include <Eigen/Core>

#include "modelgen/estimation/errors_in_variables.hpp"

namespace modelgen {

struct ErrorsInVariablesAccess {
  // Residuals (and Jacobian rows) of samples [begin, end) into r and J at row (begin * dof).
  static bool evaluate_block(const ErrorsInVariablesObjective& o, const double* theta,
                             Eigen::Index begin, Eigen::Index end, double* r, double* J);
  // Covariance of the score J' r at theta from the noise of the observations, linearised;
  // nullopt when the noise has no lines (errors_in_variables_score.cpp).
  static std::optional<Eigen::MatrixXd> score_covariance(const ErrorsInVariablesObjective& o,
                                                         const Eigen::VectorXd& theta,
                                                         const Eigen::MatrixXd& J);
};

}  // namespace modelgen
