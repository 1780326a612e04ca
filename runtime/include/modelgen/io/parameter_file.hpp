// Parameter files of modelid: true parameters for simulation and estimates from `fit`, read as
// base parameters of a model.
#pragma once

#include <string>

#include <Eigen/Core>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::io {

/// Reads base parameters from a JSON file holding one of
///   {"standard": {"ZZ1": 1.2, ...}}   standard parameters by name, missing ones 0, converted
///                                      through the regrouping relations;
///   {"base": {"ZZ1R": 1.2, ...}}       base parameters by name, missing ones 0;
///   {"parameters": [{"name": "ZZ1R", "value": 1.2}, ...]}   an estimate written by `fit`.
/// Throws InputError naming the file, line and column and the problem: a syntax error, a
/// number beyond a double, a key or parameter given twice, more than one of the three forms,
/// an empty or unknown parameter name (with the closest name).
Eigen::VectorXd read_base_parameters(const std::string& path, const IdentificationModel& model);

/// Throws InputError at the file's "standard" (or "base", "parameters") entry when its values
/// cannot be those of a physical robot (modelgen/model/physical_consistency.hpp): a standard
/// set is judged whole (per link mass, centre of mass and inertia; rotor inertias and friction
/// >= 0); of base parameters only those that are a standard parameter themselves (drive
/// parameters that are not regrouped) can be judged. The message names each link and
/// condition. `path` must have passed read_base_parameters; `description` is the one `model`
/// was made from (nothing is judged when its parameters are not the model's).
void check_physically_possible(const std::string& path, const IdentificationModel& model,
                               const RobotModel& description);

}  // namespace modelgen::io
