// modelid simulate --drive: the simulated truth of a drive-parameter file and the motor torques
// of the nonlinear drive model F of Swevers et al. 2002 (eq. 12: rigid-body gear torques, the
// coupling eq. 9-10, the efficiency eq. 8, rotor inertia and friction eq. 5-7), with a load
// (eq. 3) on the description's payload link.
#pragma once

#include <string>

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/ml/drive_model.hpp"
#include "modelgen/model/robot_model.hpp"
#include "runtime/cli/common/progress.hpp"

namespace modelgen::internal {

/// The truth `simulate --drive` simulates.
struct DriveTruth {
  /// model.param_names() values: the file's values, 0 where not given except Rzj = 1, and the
  /// load's standard parameters (standard_from_load) added to the payload link's XXj..Mj.
  Eigen::VectorXd theta;
  /// One line saying which values were not in the file and what they were taken as (links all
  /// of whose inertial parameters are missing by number, the rest by name); empty if none.
  std::string note;
};

/// Reads `path` ({"name": value} over ml_param_names(model), read_drive_parameter_values) for
/// `model`, the drive model of `description`. Throws std::runtime_error naming `path` for an
/// unknown name, an efficiency Rzj that is not positive, a load (any load_* given) when
/// `description` names no payload link or the load is physically inconsistent
/// (physical_consistency_warnings, listed).
DriveTruth read_drive_truth(const std::string& path, const modelgen::RobotModel& description,
                            const DriveModel& model);

/// Motor torques tau_M (samples x dof, N m, link side) of `model` at `theta` for every sample
/// of `x` (its q, dq, ddq, joint side), bound to the model a block of samples at a time;
/// `progress` counts samples.
Eigen::MatrixXd motor_torques(DriveModel& model, const Trajectory& x, const Eigen::VectorXd& theta,
                              Progress& progress);

}  // namespace modelgen::internal
