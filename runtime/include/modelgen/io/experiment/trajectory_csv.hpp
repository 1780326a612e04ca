// Trajectories from and to CSV files, checked row by row, errors positioned.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"

namespace modelgen::io {

/// Limits of one data file: its size, and its samples (each sample's regressor rows take about
/// 3 KB for six axes, so a million samples take 3 GB before the decimation).
inline constexpr std::uintmax_t kMaxDataFileBytes = std::uintmax_t{1} << 30;  // 1 GiB
inline constexpr std::size_t kMaxDataRows = 1000000;

/// Whether a data file must carry torques (or currents).
enum class EffortColumns { kRequired, kOptional };

/// Reads a CSV file with a header row naming its columns: `t`, `q1`..`qn`, then either
/// `tau1`..`taun` (torques) or `i1`..`in` (motor currents, converted by to_joint_side in
/// modelgen/data/joint_side.hpp), and optionally `dq1`..`dqn` and `ddq1`..`ddqn`, and the
/// reference positions `qr1`..`qrn` of a closed-loop record (all or none; any order;
/// other columns are ignored). Comma separated, one sample per line, time strictly increasing,
/// every value finite. With EffortColumns::kOptional a file without tau and i columns is
/// accepted (Measured::kNothing).
/// Throws DataError naming the file, line and column for: a missing column (listing the header's
/// columns), a column named twice, dq without ddq (or some axes only), torque and current
/// columns mixed, a row with the wrong number of fields, a value that is not a number, NaN or
/// infinity, time not increasing, a step between time stamps longer than 100 median steps (a
/// hole resampling would fill with invented samples), fewer than 3 samples, more than
/// kMaxDataRows samples or kMaxDataFileBytes bytes, and (EffortColumns::kRequired) torques or
/// currents that are all zero.
Trajectory read_trajectory_csv(const std::string& path, int dof,
                               EffortColumns effort = EffortColumns::kRequired);

/// Writes a trajectory as CSV, shortest round-trip numbers: t, q, dq and ddq (when
/// has_velocity), tau, and qr when the trajectory has reference positions.
void write_trajectory_csv(const std::string& path, const Trajectory& trajectory);

}  // namespace modelgen::io
