// Chooses the description loader by file extension and reads files whole.

#include "modelgen/model/load_robot.hpp"

#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "modelgen/model/description_limits.hpp"
#include "runtime/model/mdh_yaml_loader.hpp"
#include "runtime/model/urdf_loader.hpp"

namespace modelgen {

std::string read_source_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError({path}, "is a directory, not a robot description");
  }
  // Read whole and parsed in memory: a limit keeps a wrong file from exhausting it.
  if (const std::uintmax_t size = std::filesystem::file_size(path, ec);
      !ec && size > kMaxDescriptionBytes) {
    throw InputError({path}, "the file has " + std::to_string(size) +
                                 " bytes, beyond the limit of " +
                                 std::to_string(kMaxDescriptionBytes) +
                                 " bytes for a robot description (README, Limits)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path}, "cannot open the file (does it exist and is it readable?)");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw InputError({path}, "error while reading the file");
  return bytes.str();
}

RobotModel load_robot_text(const std::string& path, const std::string& text,
                           const LoadOptions& options) {
  if (!(options.angle_tolerance >= 0 && options.angle_tolerance < std::numbers::pi / 4)) {
    // Beyond pi/4 every angle would be within reach of some quarter turn.
    throw std::invalid_argument("angle tolerance must be in [0, pi/4)");
  }
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension == ".yaml" || extension == ".yml") {
    if (!options.base_link.empty() || !options.tip_link.empty()) {
      throw InputError({path}, "--base and --tip apply to URDF descriptions only");
    }
    RobotModel model = load_mdh_yaml(path, text, options.angle_tolerance);
    if (!options.name.empty()) {
      check_robot_name(options.name, {path});
      model.name = options.name;
      // The note on the file's own name (robot_identifier) says what --name has just decided.
      std::erase_if(model.notes, [](const DescriptionNote& note) {
        return note.message.starts_with("robot name '");
      });
    }
    return model;
  }
  if (extension == ".urdf" || extension == ".xml") return load_urdf(path, text, options);
  throw InputError({path}, "unknown description format '" + extension +
                               "': expected .yaml/.yml (modified DH) or .urdf");
}

RobotModel load_robot(const std::string& path, const LoadOptions& options) {
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension != ".yaml" && extension != ".yml" && extension != ".urdf" && extension != ".xml") {
    return load_robot_text(path, "", options);  // refuses the format before reading
  }
  return load_robot_text(path, read_source_file(path), options);
}

}  // namespace modelgen
