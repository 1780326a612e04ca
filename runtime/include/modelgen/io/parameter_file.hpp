// Parameter files of modelid: true parameters for simulation and estimates from `fit`, read as
// base parameters of a model.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/io/json_file.hpp"
#include "modelgen/model/error.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::io {

/// Reads base parameters from a JSON file holding one of
///   {"standard": {"ZZ1": 1.2, ...}}   standard parameters by name, missing ones 0, converted
///                                      through the regrouping relations;
///   {"base": {"ZZ1R": 1.2, ...}}       base parameters by name, missing ones 0;
///   {"parameters": [{"name": "ZZ1R", "value": 1.2}, ...]}   an estimate written by `fit`,
///                                      every base parameter.
/// Throws InputError naming the file, line and column and the problem: a syntax error, a
/// number beyond a double, a key or parameter given twice, more than one of the three forms,
/// an empty or unknown parameter name (with the closest name), a base parameter missing from
/// "parameters" (each missing one named).
Eigen::VectorXd read_base_parameters(const std::string& path, const IdentificationModel& model);
/// The same from a document already read (read_json_document): a command that checks, reads and
/// judges one parameter file parses it once and hands the document to each step.
Eigen::VectorXd read_base_parameters(const JsonDocument& document,
                                     const IdentificationModel& model);

/// What check_physically_possible finds, without throwing.
struct PhysicalProblems {
  std::string key;                    ///< the entry judged: "standard", "base" or "parameters"
  SourceLocation where;               ///< its position in the file
  std::vector<std::string> problems;  ///< one per violated condition, naming link and parameter
  /// "these parameters cannot be those of a physical robot: <problems, '; '-separated>".
  std::string text() const;
};

/// The conditions the values of the parameter file at `path` break, as
/// check_physically_possible judges them; no problems (and an empty key) when `description`'s
/// parameters are not the model's.
PhysicalProblems physical_problems(const std::string& path, const IdentificationModel& model,
                                   const RobotModel& description);
/// The same for a document already read.
PhysicalProblems physical_problems(const JsonDocument& document, const IdentificationModel& model,
                                   const RobotModel& description);

/// Throws InputError at the file's "standard" (or "base", "parameters") entry when its values
/// cannot be those of a physical robot (modelgen/model/physical_consistency.hpp): a standard
/// set is judged whole (per link mass, centre of mass and inertia; rotor inertias and friction
/// >= 0); of base parameters only those that are a standard parameter themselves (drive
/// parameters that are not regrouped) can be judged. The message names each link and
/// condition. `path` must have passed read_base_parameters; `description` is the one `model`
/// was made from (nothing is judged when its parameters are not the model's).
void check_physically_possible(const std::string& path, const IdentificationModel& model,
                               const RobotModel& description);
/// The same for a document already read.
void check_physically_possible(const JsonDocument& document, const IdentificationModel& model,
                               const RobotModel& description);

}  // namespace modelgen::io
