// Loads a robot described by a Khalil-Kleinfinger modified DH table in YAML (format in
// README.md) into a RobotModel.
#pragma once

#include <string>

#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen {

/// Parses `text` read from `path` (the path is only used in messages). Throws InputError with
/// file, line and column for syntax errors, unknown keys (with the closest valid key), wrong
/// types, missing fields, bad coupling matrices and antecedent cycles. Numeric alpha and theta
/// within `angle_tolerance` of a multiple of pi/2 become that multiple, with a note.
RobotModel load_mdh_yaml(const std::string& path, const std::string& text, double angle_tolerance = kDefaultAngleTolerance);

}  // namespace modelgen
