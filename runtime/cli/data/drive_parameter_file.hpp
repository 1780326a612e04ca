// Drive-model parameter files of modelid: {"name": value, ...} over ml_param_names() (link
// inertial parameters XXj..Mj, JMj, Rvj, Rcj, Rzj, load_m, load_cx, ...), read for
// `fit --method ml --known` (a-priori values) and `simulate --drive` (the simulated truth).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen::internal {

/// The values in `path`; every name must be one of `names`. Throws InputError naming
/// the file, line and column and the problem (not JSON, not an object, an unknown name, a value that is not a
/// finite number).
std::map<std::string, double> read_drive_parameter_values(const std::string& path,
                                                          const std::vector<std::string>& names);

/// What makes `values` (drive-model names, as read above) impossible for a robot with `tree`,
/// one entry per violated condition: a link whose XXj..Mj are all given that no mass
/// distribution has (modelgen/model/physical_consistency.hpp), JMj, Rvj, Rcj below zero, Rzj
/// outside (0, 1], a load (all ten given) that cannot be (modelgen/ml/load_parameters.hpp).
std::vector<std::string> drive_parameter_violations(const std::map<std::string, double>& values,
                                                    const RigidBodyTree& tree);

}  // namespace modelgen::internal
