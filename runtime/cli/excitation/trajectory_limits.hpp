// A Fourier excitation against the description's joint limits, as the commands say it:
// simulate refuses one that leaves them, check-trajectory prints the use of each, design
// verifies its result. The numbers come from modelgen/excitation/limit_use.hpp.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "modelgen/excitation/limit_use.hpp"
#include "modelgen/excitation/torque_use.hpp"
#include "modelgen/model/command_line.hpp"
#include "runtime/cli/common/model_source.hpp"

namespace modelgen::internal {

/// "joint 5 ('J5')" (j 0-based).
std::string joint_label(const ModelSource& source, int j);

/// One "modelid COMMAND: note:" line per position or velocity limit key some joints lack
/// (those are not checked; a missing ddq is not mentioned, URDF cannot hold one), or one line
/// when the model has no description at all. Returns true when something was noted.
bool note_missing_limits(std::ostream& err, const std::string& command, const ModelSource& source);

/// Throws std::runtime_error when `trajectory` (read from `path`) uses more than `margin` of
/// any limit of `source` on the dense grid: one line per joint and key left, "PATH: error:
/// joint 5 ('J5') leaves its q limit: q = 9 at t = 1.25 s, limit 2.44", then what to do.
void refuse_beyond_limits(const std::string& path, const FourierTrajectory& trajectory,
                          const ModelSource& source, const std::string& advice);

/// The table of limit uses of `extremes` against `limits` (one per joint): each limit's peak,
/// limit and use in percent, a '!' after a use above 100%; a key without a limit shows its
/// peak and "(none)". Returns the number of limits exceeded.
int print_limit_use(std::ostream& out, const ModelSource& source,
                    const std::vector<JointExtremes>& extremes, const std::vector<JointLimits>& limits);

/// The table of a-priori torque use: per joint, the peak |tau| over one period, when it occurs,
/// the effort limit and the use in percent, a '!' after a use above 100%; a joint without an
/// effort limit shows its peak and "(none)". Returns the number of effort limits exceeded.
int print_torque_use(std::ostream& out, const ModelSource& source,
                     const std::vector<TorquePeak>& peaks, const std::vector<JointLimits>& limits);

/// --ddq-limit A or A1,..,An (design, check-trajectory): acceleration limits for every joint
/// of `limits` (which must not be empty), replacing the description's (URDF has none). No-op
/// without the option; UsageError for a wrong count or a limit that is not positive.
void apply_ddq_limit_option(const CommandLine& args, std::vector<JointLimits>& limits);

}  // namespace modelgen::internal
