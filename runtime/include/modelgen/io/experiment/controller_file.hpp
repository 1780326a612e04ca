// The joint controller of a closed-loop experiment, from controller.yaml (issue 13).
#pragma once

#include <string>
#include <vector>

#include "modelgen/closed_loop/pid_controller.hpp"

namespace modelgen::io {

/// Reads {type: pid, sample_time: S, kp: [..], ki: [..], kd: [..]} with one gain per joint
/// (joint side: N m/rad, N m/(rad s), N m s/rad). Throws modelgen::InputError naming the file,
/// line and column for a syntax error, a missing, unknown or repeated key, another type, a
/// sample time outside 1e-6 to 1 s (above it: a typo for milliseconds), a list
/// whose length is not `dof`, a gain that is negative or not a number, kp = 0.
/// A sample time of 0.1 s or more (no joint controller runs that slowly; 1 meant as 1 ms
/// is the likely slip) is accepted with a "file:line:column: warning: ..." line appended to
/// `warnings` when given, for the caller to print.
PidGains read_controller(const std::string& path, int dof,
                         std::vector<std::string>* warnings = nullptr);

}  // namespace modelgen::io
