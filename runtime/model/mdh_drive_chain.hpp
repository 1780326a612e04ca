// The drive chain of an MDH YAML description (its 'drives' map): gear ratios, the coupling
// matrix in either of its two written forms, torque constants and joint offsets. Private to
// the MDH YAML loader.
#pragma once

#include <yaml-cpp/yaml.h>

#include "modelgen/model/robot_model.hpp"
#include "runtime/model/yaml_reader.hpp"

namespace modelgen {

/// Fills `model.drives` from `node` (absent: no drives, motor and joint sides coincide). The
/// joints must have been read. Throws InputError at the offending value.
void read_drive_chain(const YamlReader& in, const YAML::Node& node, RobotModel& model);

}  // namespace modelgen
