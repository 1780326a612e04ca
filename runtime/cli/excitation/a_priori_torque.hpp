// The a-priori torques the commands compare with the description's effort limits: from the
// description's own values (URDF inertials, YAML `known:`), and only when it gives the
// inertial parameters of every link; torques from guessed masses would be worse than none.
#pragma once

#include <optional>
#include <ostream>
#include <string>

#include <Eigen/Core>

#include "runtime/cli/common/model_source.hpp"

namespace modelgen::internal {

/// The base parameters a-priori torques are computed with, when some joint of `source` has an
/// effort limit and its description gives every inertial parameter (XX..M) of every link but
/// the payload's (missing payload values: no load); drive and friction values it does not give
/// are taken as 0. When effort limits are given but inertial values are missing, prints one
/// "modelid COMMAND: note:" line on `err` naming the first missing value and returns nullopt;
/// without effort limits, nullopt and no note.
std::optional<Eigen::VectorXd> effort_check_parameters(std::ostream& err, const std::string& command,
                                                       const ModelSource& source);

}  // namespace modelgen::internal
