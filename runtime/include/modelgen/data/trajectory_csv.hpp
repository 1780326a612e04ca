// Trajectories from and to CSV files, checked row by row, errors positioned.
#pragma once

#include <string>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"

namespace modelgen {

/// Whether a data file must carry torques (or currents).
enum class EffortColumns { kRequired, kOptional };

/// Reads a CSV file with a header row naming its columns: `t`, `q1`..`qn`, then either
/// `tau1`..`taun` (torques) or `i1`..`in` (motor currents, converted by to_joint_side in
/// modelgen/data/joint_side.hpp), and optionally `dq1`..`dqn` and `ddq1`..`ddqn` (any order;
/// other columns are ignored). Comma separated, one sample per line, time strictly increasing,
/// every value finite. With EffortColumns::kOptional a file without tau and i columns is
/// accepted (Measured::kNothing).
/// Throws DataError naming the file, line and column for: a missing column (listing the header's
/// columns), torque and current columns mixed, a row with the wrong number of fields, a value
/// that is not a number, NaN or infinity, time not increasing, fewer than 3 samples.
Trajectory read_trajectory_csv(const std::string& path, int dof,
                               EffortColumns effort = EffortColumns::kRequired);

/// Writes a trajectory as CSV (t, q, dq, ddq, tau columns, shortest round-trip numbers).
void write_trajectory_csv(const std::string& path, const Trajectory& trajectory);

}  // namespace modelgen
