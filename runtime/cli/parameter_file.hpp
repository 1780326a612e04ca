// Parameter files of modelid: true parameters for simulation and estimates from `fit`, read as
// base parameters of a model.
#pragma once

#include <string>

#include <Eigen/Core>

#include "modelgen/model/identification_model.hpp"

namespace modelgen::internal {

/// Reads base parameters from a JSON file holding one of
///   {"standard": {"ZZ1": 1.2, ...}}   standard parameters by name, missing ones 0, converted
///                                      through the regrouping relations;
///   {"base": {"ZZ1R": 1.2, ...}}       base parameters by name, missing ones 0;
///   {"parameters": [{"name": "ZZ1R", "value": 1.2}, ...]}   an estimate written by `fit`.
/// Throws std::runtime_error naming the file and the problem (syntax error with line and
/// column, unknown parameter with the closest name).
Eigen::VectorXd read_base_parameters(const std::string& path, const IdentificationModel& model);

}  // namespace modelgen::internal
