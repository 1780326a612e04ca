// Resolves --robot: a path that exists is a description, otherwise a compiled-in model name.

#include "runtime/cli/common/model_source.hpp"

#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "modelgen/ml/loaded_drive_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/sha256.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "runtime/cli/compiled/compiled_on_first_use.hpp"

namespace modelgen::internal {

namespace {

// The moving joints' names and limits, in the order of the model's joints.
void take_limits(const RobotModel& description, int dof, ModelSource& source) {
  if (description.dof() != dof || description.joints.size() != description.tree.bodies.size()) {
    return;
  }
  source.joint_names.resize(dof);
  source.limits.resize(dof);
  for (std::size_t b = 0; b < description.joints.size(); ++b) {
    const int j = description.tree.bodies[b].dof_index;
    if (j < 0 || j >= dof) continue;
    source.joint_names[j] = description.joints[b].name;
    source.limits[j] = description.joints[b].limits;
  }
}

// The description's model: compiled on first use when `how` allows, else the numeric reference.
void take_model(const std::string& robot, const LoadOptions& options, DescriptionModel how,
                ModelSource& source) {
  auto reference = std::make_unique<ReferenceModel>(
      source.description->name, source.description->tree, sha256_hex(read_source_file(robot)),
      source.description->drives);
  if (how == DescriptionModel::kNumericAsked) {
    std::cerr << "modelid: note: --no-compile: " << robot
              << " through the numeric reference (about 100x slower in closed-loop fits and "
                 "simulation than its compiled model)\n";
  }
  if (how == DescriptionModel::kCompiled) {
    source.model = std::make_unique<CompiledOnFirstUse>(std::move(reference), robot, options);
  } else {
    source.model = std::move(reference);
  }
}

}  // namespace

std::unique_ptr<DriveModel> compiled_drive_model(const ModelSource& source) {
  const auto* compiled = dynamic_cast<const CompiledOnFirstUse*>(source.model.get());
  const ModelLibrary* library = compiled != nullptr ? compiled->library() : nullptr;
  return library != nullptr ? make_drive_model(*library) : nullptr;
}

LoadOptions description_options(const CommandLine& args) {
  LoadOptions options;
  options.angle_tolerance = angle_tolerance_option(args);
  options.name = args.one_or("--name", "");
  options.base_link = args.one_or("--base", "");
  options.tip_link = args.one_or("--tip", "");
  options.mimic_as_joint = args.has("--mimic-as-joint");
  return options;
}

ModelSource load_model_source(const std::string& robot, const CommandLine& args) {
  return load_model_source(
      robot, description_options(args),
      args.has("--no-compile") ? DescriptionModel::kNumericAsked : DescriptionModel::kCompiled);
}

ModelSource load_model_source(const std::string& robot, const LoadOptions& options,
                              DescriptionModel how) {
  ModelSource source;
  // A folder named like a compiled-in model (build/kr150 after generating it) is not a file.
  if (std::filesystem::exists(robot) && !std::filesystem::is_directory(robot)) {
    source.description = modelgen::load_robot(robot, options);
    // Rounded quarter turns taken as exact, as modelgen does with its default tolerance, so
    // a description gives the same model here as its generated code.
    for (const DescriptionNote& note : source.description->notes) {
      std::cerr << note.to_string() << "\n";
    }
    take_model(robot, options, how, source);
    take_limits(*source.description, source.model->dof(), source);
    return source;
  }
  source.model = make_shipped_model(robot);
  if (source.model != nullptr && !options.name.empty()) {
    throw UsageError{"--name applies to a description file; '" + robot +
                     "' is a compiled-in model, named '" + source.model->name() + "'"};
  }
  if (source.model != nullptr &&
      (!options.base_link.empty() || !options.tip_link.empty() || options.mimic_as_joint)) {
    throw UsageError{"--base, --tip and --mimic-as-joint apply to a URDF description file; '" +
                     robot + "' is a compiled-in model"};
  }
  if (source.model != nullptr) {
    const std::string path = shipped_description_path(robot);
    if (!path.empty()) {
      source.shipped_description = modelgen::load_robot(path);
      take_limits(*source.shipped_description, source.model->dof(), source);
    }
  }
  if (source.model == nullptr) {
    std::string names;
    for (const std::string& name : shipped_model_names()) names += " " + name;
    throw std::invalid_argument("--robot '" + robot +
                                "' is neither a description file nor a compiled-in model (" +
                                "compiled in:" + names + ")");
  }
  return source;
}

}  // namespace modelgen::internal
