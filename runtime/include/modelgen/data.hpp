// Measured (or simulated) joint trajectories from CSV files, checked row by row, and the
// derivatives the identification models need.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace modelgen {

/// A problem with a data file; what() reads "file:line (column NAME): error: message", the line
/// and column parts when known.
class DataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What the `tau` matrix of a trajectory holds.
enum class Measured {
  kTorque,   ///< torques (joint side, or motor side before to_joint_side), N m (N)
  kCurrent,  ///< motor currents in A (columns i1..in), until to_joint_side converts them
  kNothing,  ///< no effort columns: tau is zero (prediction only)
};

/// One experiment: samples x dof matrices (row s is sample s), time in seconds.
struct Trajectory {
  std::string source;  ///< file it came from
  Eigen::VectorXd t;
  Eigen::MatrixXd q, dq, ddq, tau;  ///< rad (m), rad/s, rad/s^2, N m (N)
  bool has_velocity = false;        ///< dq and ddq were in the file
  Measured measured = Measured::kTorque;
};

/// Whether a data file must carry torques (or currents).
enum class EffortColumns { kRequired, kOptional };

/// Reads a CSV file with a header row naming its columns: `t`, `q1`..`qn`, then either
/// `tau1`..`taun` (torques) or `i1`..`in` (motor currents, converted by to_joint_side in
/// modelgen/transmission.hpp), and optionally `dq1`..`dqn` and `ddq1`..`ddqn` (any order;
/// other columns are ignored). Comma separated, one sample per line, time strictly increasing,
/// every value finite. With EffortColumns::kOptional a file without tau and i columns is
/// accepted (Measured::kNothing).
/// Throws DataError naming the file, line and column for: a missing column (listing the header's
/// columns), torque and current columns mixed, a row with the wrong number of fields, a value
/// that is not a number, NaN or infinity, time not increasing, fewer than 3 samples.
Trajectory read_trajectory_csv(const std::string& path, int dof,
                               EffortColumns effort = EffortColumns::kRequired);

/// Fills dq and ddq from q by central differences (second order, unequal steps allowed) and
/// drops the first and last samples, where central differences do not exist. Used when the
/// file has no dq/ddq columns.
void differentiate(Trajectory& trajectory);

/// Writes a trajectory as CSV (t, q, dq, ddq, tau columns, shortest round-trip numbers).
void write_trajectory_csv(const std::string& path, const Trajectory& trajectory);

}  // namespace modelgen
