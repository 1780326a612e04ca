// Text table of the base parameters and their regrouping relations: what `modelgen base`
// prints.
#pragma once

#include <string>

#include "generator/description/robot_model.hpp"
#include "generator/dynamics/base_parameters.hpp"

namespace modelgen::gen {

std::string describe_base_parameters(const RobotModel& model, const BaseParameterSet& base);

}  // namespace modelgen::gen
