// Text table of the base parameters and their regrouping relations: what `modelgen base`
// prints.
#pragma once

#include <string>

#include "modelgen/model/robot_model.hpp"
#include "modelgen/model/base_parameters.hpp"
#include "generator/dynamics/closed_form_base.hpp"

namespace modelgen::gen {

/// One line per base parameter with its relation in numbers; with `closed` (MDH robots) a
/// second line with the coefficients written with d_j and r_j where the closed-form rules give
/// them (terms the numeric method regroups beyond the rules keep their number).
std::string describe_base_parameters(const RobotModel& model, const BaseParameterSet& base,
                                     const ClosedFormRelations* closed = nullptr);

}  // namespace modelgen::gen
