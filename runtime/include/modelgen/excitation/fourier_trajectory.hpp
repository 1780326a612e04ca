// Periodic excitation trajectories: finite Fourier series per joint (Swevers et al. eq. 15-17),
// with positions, velocities and accelerations analytic.
#pragma once

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"

namespace modelgen {

/// q_j(t) = q0_j + sum_{l=1..L} a_jl / (l wf) sin(l wf t) - b_jl / (l wf) cos(l wf t), with
/// wf = 2 pi / period (Swevers eq. 15); dq and ddq are its exact derivatives (eq. 16-17).
struct FourierTrajectory {
  double period = 10.0;  ///< s
  Eigen::VectorXd q0;    ///< dof offsets
  Eigen::MatrixXd a, b;  ///< dof x L coefficients (rad/s)

  void evaluate(double t, Eigen::VectorXd& q, Eigen::VectorXd& dq, Eigen::VectorXd& ddq) const;
};

/// Samples `trajectory` every `sample_time` seconds for `duration` seconds (t = 0, dt, ...,
/// t < duration); torques are left at zero for the caller to fill.
Trajectory sample(const FourierTrajectory& trajectory, double sample_time, double duration);

}  // namespace modelgen
