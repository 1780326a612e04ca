// Loads a URDF (through urdfdom, with a TinyXML2 pass first for line numbers) into a
// RobotModel: general fixed transform plus joint axis per body, inertials converted to the
// standard parameters about each body frame's origin.
#pragma once

#include <string>

#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen {

/// Parses `text` read from `path` (the path is only used in messages).
RobotModel load_urdf(const std::string& path, const std::string& text, const LoadOptions& options);

}  // namespace modelgen
