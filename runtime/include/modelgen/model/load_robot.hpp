// Entry point for reading any robot description: picks the loader from the file extension; and
// the raw bytes of a description, for its SHA-256.
#pragma once

#include <string>

#include "modelgen/model/robot_model.hpp"

namespace modelgen {

struct LoadOptions {
  std::string base_link;  ///< URDF: root of the kinematic tree to model; empty = URDF root
  std::string tip_link;   ///< URDF: keep only the chain from base to this link; empty = all
  std::string name;       ///< overrides the robot name (URDF names need not be identifiers)
};

/// Loads `path` (.yaml/.yml: MDH description; .urdf: URDF) into a validated RobotModel.
/// Throws InputError naming the file, line and field on any problem.
RobotModel load_robot(const std::string& path, const LoadOptions& options = {});

/// The whole file as bytes; InputError if it cannot be read.
std::string read_source_file(const std::string& path);

}  // namespace modelgen
