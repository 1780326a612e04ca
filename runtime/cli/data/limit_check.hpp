// Measured positions and velocities against the description's joint limits: data outside them
// are seldom what the user meant (motor-side data read as joint data, degrees as radians).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "modelgen/data/joint_side.hpp"
#include "runtime/cli/common/model_source.hpp"
#include "runtime/cli/data/data_files.hpp"

namespace modelgen::internal {

/// For each experiment (joint side, as prepared) and joint with limits in `source`: one
/// "modelid COMMAND: warning:" line on `err` when its position leaves [lower, upper] or its
/// speed exceeds the velocity limit by more than 1% (measured data overshoot a little), naming
/// the file, the joint, the extreme value, the limit and the likely cause: positions measured
/// on the motor side (without --motor-side when `side` is the joint side), degrees read as
/// radians. Returns the number of lines written.
int warn_beyond_limits(std::ostream& err, const std::string& command, const ModelSource& source,
                       const Experiments& experiments, Side side);

}  // namespace modelgen::internal
