// The a-priori values of an MDH YAML description (its 'known' map), checked to describe real
// bodies. Private to the MDH YAML loader.
#pragma once

#include <yaml-cpp/yaml.h>

#include "modelgen/model/robot_model.hpp"
#include "runtime/model/yaml_reader.hpp"

namespace modelgen {

/// Sets `model.known_values` from `node`, a map of standard parameter names to values. The
/// standard parameters must have been built. Throws InputError at the offending name or value.
void read_known_values(const YamlReader& in, const YAML::Node& node, RobotModel& model);

}  // namespace modelgen
