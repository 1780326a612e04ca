// What modelid design prints of a design (design_report.cpp): the conditioning it reached and
// its floor, the same criterion on a --compare trajectory, the limits it had to shrink for, the
// expected standard deviations and the use of every limit and of the effort limits.
#pragma once

#include <ostream>
#include <string>

#include "modelgen/excitation/excitation_design.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "runtime/cli/common/model_source.hpp"

namespace modelgen::internal {

/// A design with what it was made from.
struct DesignReport {
  const ModelSource& source;
  const ExcitationDesignProblem& problem;
  const ExcitationDesign& design;
  const FourierTrajectory& trajectory;  ///< the design as a trajectory
};

/// The sampling, the base parameters excited, the criterion before and after, and the floor
/// set by the most collinear pair of columns.
void print_conditioning(std::ostream& out, const DesignReport& report);

/// The same criterion on `compared` (read from `path`): the same columns and samples per period.
void print_comparison(std::ostream& out, const DesignReport& report,
                      const FourierTrajectory& compared, const std::string& path);

/// The joints whose oscillation shrank to stay inside a limit on the dense grid.
void print_shrinks(std::ostream& out, const DesignReport& report);

/// sigma^2 (W^T W)^-1 of one period with `noise` on every torque sample, with %std of the
/// description's a-priori values when it has them.
void print_expected_precision(std::ostream& out, const DesignReport& report, double noise);

/// The use of every joint limit on the dense grid, and of the effort limits by the a-priori
/// torques when the description has inertial values.
void print_limits_and_torques(std::ostream& out, const DesignReport& report);

}  // namespace modelgen::internal
