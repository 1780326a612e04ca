// What --robot names: a compiled-in generated model ("kr150") or a description file (any
// YAML/URDF, through the numeric reference).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "modelgen/ml/drive_model.hpp"
#include "modelgen/model/command_line.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::internal {

struct ModelSource {
  std::unique_ptr<IdentificationModel> model;
  std::optional<modelgen::RobotModel> description;  ///< when --robot was a file
  /// For a compiled-in model, its description in the source tree when it is there
  /// (shipped_description_path).
  std::optional<modelgen::RobotModel> shipped_description;
  /// Joint names and limits, one per joint of the model: from the description file, or for a
  /// compiled-in model from its description in the source tree when it is there
  /// (shipped_description_path); empty when unknown.
  std::vector<std::string> joint_names;
  std::vector<JointLimits> limits;

  /// The description behind the model: the file, else the shipped one; null when neither.
  const modelgen::RobotModel* any_description() const {
    if (description) return &*description;
    return shipped_description ? &*shipped_description : nullptr;
  }
};

/// How a description file's model is evaluated.
enum class DescriptionModel {
  /// generated, compiled and cached, or loaded from the cache, when first evaluated
  /// (runtime/cli/compiled/compiled_on_first_use.hpp); the numeric reference if it cannot be
  kCompiled,
  kNumericAsked,  ///< the numeric reference, as --no-compile asked (said in a note)
  kNumeric,       ///< the numeric reference, for commands that evaluate the model a few times
};

/// Throws modelgen::InputError for a file that does not load, std::invalid_argument for a name
/// that is neither a file nor a compiled-in model (the message lists the compiled-in ones).
/// A description file is read with `options` (--angle-tolerance, --name, --base, --tip,
/// --mimic-as-joint: description_options), its notes printed on standard error; a compiled-in
/// model refuses --name, --base, --tip and --mimic-as-joint (UsageError).
ModelSource load_model_source(const std::string& robot, const LoadOptions& options = {},
                              DescriptionModel how = DescriptionModel::kCompiled);

/// The drive model of a description file's compiled model (compiling it now if that was not
/// tried yet); null for a compiled-in model, on the numeric reference and when there is no
/// compiled model.
std::unique_ptr<DriveModel> compiled_drive_model(const ModelSource& source);

/// The options every command reads a description with: --angle-tolerance, --name, --base,
/// --tip and --mimic-as-joint.
LoadOptions description_options(const CommandLine& args);

/// load_model_source(robot, description_options(args), kCompiled or, with --no-compile,
/// kNumericAsked): the way commands that evaluate the model many times load it.
ModelSource load_model_source(const std::string& robot, const CommandLine& args);

}  // namespace modelgen::internal
