// Description file -> generated files, as the command line and the tests run it.

#include "generator/generate.hpp"

#include <algorithm>
#include <filesystem>

#include "generator/estimate/estimate_file.hpp"
#include "generator/functions/entry_points.hpp"
#include "modelgen/model/command_line.hpp"
#include "modelgen/model/number_text.hpp"
#include "modelgen/model/sha256.hpp"

namespace modelgen::gen {

namespace {

// The loadable table points to the double entry points the runtime's adapters call.
void check_loadable(const GenerationOptions& generation) {
  if (!generation.loadable) return;
  if (!generation.functions.empty()) {
    throw UsageError("--loadable needs every function the runtime calls: leave out --functions");
  }
  if (generation.scalar == "float") {
    throw UsageError("--loadable needs the double entry points: use --scalar double or both");
  }
}

}  // namespace

std::string normalized_command(const std::string& robot_path, const LoadOptions& options,
                               const GenerationOptions& generation) {
  const std::string& scalar = generation.scalar;
  const std::string& params_path = generation.params_path;
  const std::vector<std::string>& functions = generation.functions;
  std::string command =
      "modelgen " + std::filesystem::path(robot_path).filename().string() + " -o <dir>";
  if (!options.name.empty()) command += " --name " + options.name;
  if (!options.base_link.empty()) command += " --base " + options.base_link;
  if (!options.tip_link.empty()) command += " --tip " + options.tip_link;
  if (options.mimic_as_joint) command += " --mimic-as-joint";
  if (scalar != "both") command += " --scalar " + scalar;
  if (options.angle_tolerance != kDefaultAngleTolerance) {
    command += " --angle-tolerance " + shortest_text(options.angle_tolerance);
  }
  // The file name only: no directory of the machine that generated; the banner's hash says
  // which estimate it was.
  if (!params_path.empty()) {
    command += " --params " + std::filesystem::path(params_path).filename().string();
  }
  if (!functions.empty()) {
    command += " --functions ";
    for (std::size_t i = 0; i < functions.size(); ++i) command += (i ? "," : "") + functions[i];
  }
  if (generation.loadable) command += " --loadable";
  return command;
}

GeneratedModel generate_from_file(const std::string& robot_path, const LoadOptions& options,
                                  const GenerationOptions& generation) {
  const std::string& scalar = generation.scalar;
  const std::string& params_path = generation.params_path;
  check_loadable(generation);
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
  input.functions = select_functions(generation.functions, !params_path.empty());
  input.loadable = generation.loadable;
  GenerationOptions normalized = generation;
  normalized.functions = input.functions.asked;
  input.command_line = normalized_command(robot_path, options, normalized);
  if (!params_path.empty()) {
    input.estimate = read_estimate_file(params_path, robot_path, sha256_hex(input.input_bytes));
  }
  return emit_model(model, input);
}

}  // namespace modelgen::gen
