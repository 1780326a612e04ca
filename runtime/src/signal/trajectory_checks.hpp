// What every signal step checks on its input trajectory before working on it, and the one
// message form of its errors: "SOURCE: error: message".
#pragma once

#include <string>

#include <Eigen/Core>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"

namespace modelgen::detail {

/// A number for messages, printf's %.6g.
std::string format(double value);

/// Throws DataError "SOURCE: error: message", SOURCE the trajectory's source or "trajectory".
[[noreturn]] void fail(const Trajectory& x, const std::string& message);

/// Every matrix has one row per time and q, tau (when `torque`) and dq, ddq (when present) the
/// same columns; else fail() saying which is not.
void check_shapes(const Trajectory& x, bool torque);

/// The first non-finite entry of `m` (samples x axes) is reported as sample, time and column
/// PREFIX<axis>.
void check_finite(const Trajectory& x, const Eigen::MatrixXd& m, const char* prefix);

}  // namespace modelgen::detail
