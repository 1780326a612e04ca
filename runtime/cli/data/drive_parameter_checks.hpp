// The physical checks of drive-model parameter values (modelgen/io/drive_parameter_file.hpp).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen::internal {

/// What makes `values` (drive-model names, as read_drive_parameter_values gives them) impossible
/// for a robot with `tree`, one entry per violated condition: a link whose XXj..Mj are all given
/// that no mass distribution has (modelgen/model/physical_consistency.hpp), JMj, Rvj, Rcj below
/// zero, Rzj outside (0, 1], a load (all ten given) that cannot be
/// (modelgen/ml/load_parameters.hpp).
std::vector<std::string> drive_parameter_violations(const std::map<std::string, double>& values,
                                                    const RigidBodyTree& tree);

}  // namespace modelgen::internal
