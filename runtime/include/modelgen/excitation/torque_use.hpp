// The joint torques a periodic excitation asks for, from a-priori parameters: the peak |tau_j|
// of each joint on the dense grid of limit_use.hpp (limit_grid_points), to compare with the
// description's effort limits before the robot is asked for them.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen {

/// The largest |tau_j| of one joint over one period, and the first time it occurs.
struct TorquePeak {
  double peak = 0, time = 0;
};

/// The peaks of tau = model.inverse_dynamics(q, dq, ddq, beta) along `trajectory` on
/// limit_grid_points(trajectory, rate) points of one period, one per joint. `beta` holds
/// model.num_base_params() values.
std::vector<TorquePeak> torque_peaks(const IdentificationModel& model, const Eigen::VectorXd& beta,
                                     const FourierTrajectory& trajectory, double rate = 1000.0);

}  // namespace modelgen
