// modelid export for a modified DH YAML description: the identified standard parameters as its
// `known:` section, the rest of the file kept byte for byte.
#pragma once

#include <string>

#include <Eigen/Core>

#include "modelgen/model/robot_model.hpp"

namespace modelgen {

/// The YAML `text` (read from `path`, loaded as `description`) with a `known:` section holding
/// every value of `standard` (one per description parameter, in its order), grouped by link
/// under a comment naming the joint, the section introduced by the comment lines of `note`.
/// A top-level `known:` that is there is replaced, with its comments (up to the next top-level
/// key, less the blank and column-0 comment lines just before that key; with the comment above
/// it when that starts "# Identified by modelid export", as `note` should); otherwise the section
/// is added at the end. Throws InputError when `known` shares a line with another top-level key
/// (a flow-style top level), which cannot be replaced without rewriting the rest.
std::string identified_yaml(const std::string& path, const std::string& text,
                            const RobotModel& description, const Eigen::VectorXd& standard,
                            const std::string& note);

}  // namespace modelgen
