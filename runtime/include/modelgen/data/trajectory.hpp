// One measured (or simulated) experiment: joint trajectories and efforts, sample by sample.
#pragma once

#include <string>

#include <Eigen/Core>

namespace modelgen {

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
  /// Reference positions of a closed-loop record (columns qr1..qrn), samples x dof; empty
  /// when the file has none.
  Eigen::MatrixXd qr;
  Measured measured = Measured::kTorque;
};

}  // namespace modelgen
