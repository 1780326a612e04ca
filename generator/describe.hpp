// Human-readable summary of a loaded robot: what `modelgen describe` prints so users can check
// their description (joint table, drive chain, friction options, standard parameters).
#pragma once

#include <string>

#include "modelgen/model/robot_model.hpp"

namespace modelgen::gen {

std::string describe(const RobotModel& model);

/// Shortest text that reads back as the same double ("0.225", "-1.5707963267948966").
std::string format_number(double value);

}  // namespace modelgen::gen
