// The joint controller of a closed-loop experiment, from controller.yaml (issue 13).
#pragma once

#include <string>

#include "modelgen/closed_loop/pid_controller.hpp"

namespace modelgen::io {

/// Reads {type: pid, sample_time: S, kp: [..], ki: [..], kd: [..]} with one gain per joint
/// (joint side: N m/rad, N m/(rad s), N m s/rad). Throws modelgen::InputError naming the file,
/// line and column for a syntax error, a missing, unknown or repeated key, another type, a
/// sample time outside 1e-6 to 1 s (above it: a typo for milliseconds), a list
/// whose length is not `dof`, a gain that is negative or not a number, kp = 0.
PidGains read_controller(const std::string& path, int dof);

}  // namespace modelgen::io
