// The residual check of fit --method ml (issue 31): the ML route's motor torque errors (Swevers
// eq. 18's residuals before their weights) brought to the joints and judged against the noise
// of the averaged periods as the other methods' residuals are (residual_check.hpp).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/model/identification_model.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

/// warn_period_residual_against_noise for one ML run: its `motor_errors` on `axes` mapped by
/// ml_joint_errors (modelgen/ml/joint_errors.hpp) with the model's drive chain, the joints it
/// leaves out unjudged, the ML route's causes and options, `unknowns` the fit's unknowns; `whose`
/// follows "the residual" (e.g. " (of approach 3)"). Returns the number of warnings.
int warn_ml_residual_against_noise(std::ostream& err, const IdentificationModel& model,
                                   const Experiments& experiments,
                                   const Eigen::MatrixXd& motor_errors,
                                   const std::vector<int>& axes, Eigen::Index unknowns,
                                   const std::string& whose);

}  // namespace modelgen::internal
