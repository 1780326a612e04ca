// Motor side to joint side: one linear map for positions, its transpose for torques (the power
// dq_motor . tau_motor = dq . tau is preserved, Gautier & Briot eq. 25-26).

#include "modelgen/data/joint_side.hpp"

#include <string>

#include <Eigen/LU>

namespace modelgen {

void to_joint_side(Trajectory& x, const DriveChain& drive, Side positions) {
  const Eigen::Index n = x.q.cols();
  if (drive.motor_from_joint.rows() != n || drive.motor_from_joint.cols() != n ||
      drive.torque_constant.size() != n || drive.joint_offset.size() != n) {
    throw DataError(x.source + ": error: the drive chain has " +
                    std::to_string(drive.motor_from_joint.rows()) + " joints, the data " +
                    std::to_string(n));
  }
  const Eigen::MatrixXd& K = drive.motor_from_joint;
  if (positions == Side::kMotor) {
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(K);
    if (!lu.isInvertible()) {
      throw DataError(x.source +
                      ": error: the drive chain's motor_from_joint matrix is singular "
                      "(rank " +
                      std::to_string(lu.rank()) +
                      "): motor positions do not determine the joint positions");
    }
    // Rows are samples: q^T = q_motor^T K^-T.
    const Eigen::MatrixXd joint_from_motor_T = lu.inverse().transpose();
    x.q = (x.q * joint_from_motor_T).rowwise() + drive.joint_offset.transpose();
    x.dq = x.dq * joint_from_motor_T;
    x.ddq = x.ddq * joint_from_motor_T;
  }
  if (x.measured == Measured::kCurrent) {
    for (Eigen::Index j = 0; j < n; ++j) {
      if (!(drive.torque_constant[j] > 0)) {
        // Positioned at the header's current column, as the CSV reader's own errors are.
        const std::string column = "i" + std::to_string(j + 1);
        throw DataError(x.source + ":1 (column " + column + "): error: column " + column +
                        " holds motor currents but the description gives no torque constant "
                        "for motor " +
                        std::to_string(j + 1) + " (drives: torque_constant)");
      }
    }
    x.tau = x.tau * drive.torque_constant.asDiagonal();
  }
  if (x.measured == Measured::kCurrent || positions == Side::kMotor) {
    // tau = K^T tau_motor; with samples as rows, tau^T = tau_motor^T K.
    if (x.measured != Measured::kNothing) x.tau = x.tau * K;
  }
  if (x.measured == Measured::kCurrent) x.measured = Measured::kTorque;
}

}  // namespace modelgen
