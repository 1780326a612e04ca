// The optional `region` key of a joint row of an MDH YAML description: where link j's mass
// must stay, in link j's frame (modelgen/model/robot_model.hpp, BodyRegion). Private to the
// YAML loader.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

#include "modelgen/model/robot_model.hpp"
#include "runtime/model/yaml_reader.hpp"

namespace modelgen {

/// `node` is either {centre: [x, y, z], semi_axes: [a, b, c]} (an ellipsoid, semi-axes > 0)
/// or {box: [[x, y, z], [x, y, z]]} (lowest and highest corner; the region is the ellipsoid
/// through its corners). Errors name the file, line and field; `context` says whose region.
BodyRegion read_region(const YamlReader& in, const YAML::Node& node, const std::string& context);

}  // namespace modelgen
