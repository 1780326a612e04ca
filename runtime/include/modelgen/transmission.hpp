// Data measured on the motor side brought to the joint side through the drive chain: coupling
// (Gautier & Briot eq. 25; Swevers et al. eq. 9-11 in the form K = diag(ratio) V^-1), motor
// torque constants for current measurements and encoder offsets.
#pragma once

#include "modelgen/data.hpp"
#include "modelgen/model/drive_chain.hpp"

namespace modelgen {

/// Where the positions (and their derivatives) and the torques of a data file were measured.
enum class Side { kJoint, kMotor };

/// Brings a trajectory to the joint side the models work on.
/// - `positions` kMotor: q = K^-1 q_motor + joint_offset, dq = K^-1 dq_motor, ddq likewise.
/// - Torques: with x.measured == Measured::kCurrent, the columns are motor currents in A and
///   tau = K^T (torque_constant .* i), whatever `positions` says (currents are motor
///   quantities); with Measured::kTorque and `positions` kMotor, tau = K^T tau_motor.
/// Sets x.measured to kTorque. Throws DataError naming x.source when a torque constant needed
/// is not positive (0: not given), K is singular, or the sizes do not match.
void to_joint_side(Trajectory& x, const DriveChain& drive, Side positions);

}  // namespace modelgen
