// --plot DIR of check-trajectory and design: q, dq and ddq of every joint over one period
// against the description's limits, as one hand-written SVG (no plotting program needed).
#pragma once

#include <string>
#include <vector>

#include "modelgen/excitation/fourier_trajectory.hpp"
#include "runtime/cli/common/model_source.hpp"

namespace modelgen::internal {

/// The SVG: one row per joint, the columns q, dq, ddq against time over one period, each limit
/// of `limits` (one per joint; q: lower and upper, dq and ddq: +-) as a dashed line. Each curve
/// is a <polyline class="q|dq|ddq" data-joint="J" data-axes="X0 SX YZ SY"> (J 1-based) whose
/// points are pixels x = X0 + SX t, y = YZ - SY value (t in s, value in rad or m per s^k; to
/// 0.01 and 0.001 px). It is drawn through `points` equally spaced instants and the instants of
/// the extremes on the dense grid of limit_use.hpp, so the plotted peaks are those
/// check-trajectory reports.
std::string trajectory_svg(const FourierTrajectory& trajectory, const ModelSource& source,
                           const std::vector<JointLimits>& limits, const std::string& title,
                           int points = 400);

/// Writes DIR/trajectory.svg (trajectory_svg), creating DIR, and returns its path. Throws
/// std::runtime_error "DIR: error: ..." when DIR cannot be created or written.
std::string write_trajectory_plot(const std::string& dir, const FourierTrajectory& trajectory,
                                  const ModelSource& source, const std::vector<JointLimits>& limits,
                                  const std::string& title);

}  // namespace modelgen::internal
