// Description file -> generated files, as the command line and the tests run it.

#include "generator/generate.hpp"

#include <filesystem>

#include "modelgen/model/number_text.hpp"

namespace modelgen::gen {

std::string normalized_command(const std::string& robot_path, const LoadOptions& options,
                               const std::string& scalar) {
  std::string command =
      "modelgen " + std::filesystem::path(robot_path).filename().string() + " -o <dir>";
  if (!options.name.empty()) command += " --name " + options.name;
  if (!options.base_link.empty()) command += " --base " + options.base_link;
  if (!options.tip_link.empty()) command += " --tip " + options.tip_link;
  if (scalar != "both") command += " --scalar " + scalar;
  if (options.angle_tolerance != kDefaultAngleTolerance) {
    command += " --angle-tolerance " + shortest_text(options.angle_tolerance);
  }
  return command;
}

GeneratedModel generate_from_file(const std::string& robot_path, const LoadOptions& options,
                                  const std::string& scalar) {
  GenerationInput input;
  if (scalar == "double") {
    input.scalars = {Scalar::kDouble};
  } else if (scalar == "float") {
    input.scalars = {Scalar::kFloat};
  } else if (scalar != "both") {
    throw InputError({}, "--scalar must be double, float or both, not '" + scalar + "'");
  }
  const RobotModel model = load_robot(robot_path, options);
  const std::filesystem::path path(robot_path);
  input.stem = path.stem().string();
  input.input_name = path.filename().string();
  input.input_bytes = read_source_file(robot_path);
  input.command_line = normalized_command(robot_path, options, scalar);
  return emit_model(model, input);
}

}  // namespace modelgen::gen
