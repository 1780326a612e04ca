// Motor-side data to joint side: positions through K^-1 and the offsets, torques through K^T,
// currents through the torque constants first. The motor-side data are made here sample by
// sample from joint-side data (the inverse maps, solved independently), and the mechanical
// power must be the same on both sides (Gautier & Briot eq. 25-26).

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "modelgen/data/joint_side.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

// The TX-40 drive chain (robots/tx40.yaml, coupled 5-6) with made-up constants and offsets.
DriveChain tx40_like() {
  DriveChain drive = DriveChain::identity(6);
  drive.motor_from_joint.diagonal() << 32, 32, 45, -48, 45, 32;
  drive.motor_from_joint(5, 4) = 32;
  drive.torque_constant << 0.9, 0.9, 0.6, 0.35, 0.3, 0.25;
  drive.joint_offset << 0.1, -0.2, 0.3, 0.0, 0.05, -0.4;
  return drive;
}

Trajectory random_joint_side(int samples) {
  test::Random random(17);
  Trajectory x;
  x.source = "joint_side.csv";
  x.t = Eigen::VectorXd::LinSpaced(samples, 0.0, 1.0);
  x.q.resize(samples, 6);
  x.dq.resize(samples, 6);
  x.ddq.resize(samples, 6);
  x.tau.resize(samples, 6);
  for (int s = 0; s < samples; ++s) {
    x.q.row(s) = random.vector(6, -2, 2);
    x.dq.row(s) = random.vector(6, -3, 3);
    x.ddq.row(s) = random.vector(6, -9, 9);
    x.tau.row(s) = random.vector(6, -50, 50);
  }
  x.has_velocity = true;
  return x;
}

TEST(DriveChain, MotorSidePositionsAndTorquesComeBackToTheJointSide) {
  const DriveChain drive = tx40_like();
  const Trajectory joint = random_joint_side(40);
  const Eigen::MatrixXd& K = drive.motor_from_joint;
  Trajectory motor = joint;
  for (Eigen::Index s = 0; s < joint.t.size(); ++s) {
    const Eigen::VectorXd q = joint.q.row(s).transpose() - drive.joint_offset;
    motor.q.row(s) = (K * q).transpose();
    motor.dq.row(s) = (K * joint.dq.row(s).transpose()).transpose();
    motor.ddq.row(s) = (K * joint.ddq.row(s).transpose()).transpose();
    // tau = K^T tau_motor, solved for tau_motor.
    motor.tau.row(s) = K.transpose().partialPivLu().solve(joint.tau.row(s).transpose()).transpose();
    // Same mechanical power on both sides.
    EXPECT_NEAR(motor.dq.row(s).dot(motor.tau.row(s)), joint.dq.row(s).dot(joint.tau.row(s)),
                1e-9 * (1 + std::abs(joint.dq.row(s).dot(joint.tau.row(s)))));
  }
  to_joint_side(motor, drive, Side::kMotor);
  EXPECT_LT((motor.q - joint.q).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((motor.dq - joint.dq).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((motor.ddq - joint.ddq).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_LT((motor.tau - joint.tau).cwiseAbs().maxCoeff(), 1e-11);
}

TEST(DriveChain, CurrentsGoThroughTheTorqueConstantsThenTheCoupling) {
  const DriveChain drive = tx40_like();
  const Trajectory joint = random_joint_side(20);
  Trajectory measured = joint;  // joint-side encoders, motor currents
  measured.measured = Measured::kCurrent;
  for (Eigen::Index s = 0; s < joint.t.size(); ++s) {
    const Eigen::VectorXd tau_motor =
        drive.motor_from_joint.transpose().partialPivLu().solve(joint.tau.row(s).transpose());
    measured.tau.row(s) = tau_motor.cwiseQuotient(drive.torque_constant).transpose();
  }
  to_joint_side(measured, drive, Side::kJoint);
  EXPECT_EQ(measured.measured, Measured::kTorque);
  EXPECT_EQ(measured.q, joint.q);  // joint-side positions untouched
  EXPECT_LT((measured.tau - joint.tau).cwiseAbs().maxCoeff(), 1e-11);
}

TEST(DriveChain, CurrentsWithoutATorqueConstantAreRefused) {
  DriveChain drive = tx40_like();
  drive.torque_constant[2] = 0;
  Trajectory x = random_joint_side(5);
  x.measured = Measured::kCurrent;
  try {
    to_joint_side(x, drive, Side::kJoint);
    ADD_FAILURE() << "currents converted without a torque constant";
  } catch (const DataError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("joint_side.csv"), std::string::npos) << what;
    EXPECT_NE(what.find("column i3"), std::string::npos) << what;
    EXPECT_NE(what.find("torque_constant"), std::string::npos) << what;
  }
}

// The generated models carry the drive chain of their description, as the loader read it.
TEST(DriveChain, GeneratedModelsCarryTheDescriptionsDriveChain) {
  const std::pair<const char*, const char*> cases[] = {{"tx40", "robots/tx40.yaml"},
                                                       {"kr150", "robots/kr150.yaml"}};
  for (const auto& [name, path] : cases) {
    const modelgen::RobotModel description = modelgen::load_robot(test::source_path(path));
    const std::unique_ptr<IdentificationModel> model = internal::make_shipped_model(name);
    ASSERT_NE(model, nullptr);
    const DriveChain& drive = model->drive_chain();
    EXPECT_LT((drive.motor_from_joint - description.drives.motor_from_joint).cwiseAbs().maxCoeff(),
              1e-15)
        << name;
    for (int j = 0; j < model->dof(); ++j) {
      EXPECT_EQ(drive.torque_constant[j], description.drives.torque_constant[j]) << name;
      EXPECT_EQ(drive.joint_offset[j], description.drives.joint_offset[j]) << name;
    }
  }
  // The TX-40's eq. 25 coupling: motor 6 turns with joints 5 and 6.
  const std::unique_ptr<IdentificationModel> tx40 = internal::make_shipped_model("tx40");
  EXPECT_EQ(tx40->drive_chain().motor_from_joint(5, 4), 32.0);
  EXPECT_EQ(tx40->drive_chain().motor_from_joint(3, 3), -48.0);
}

}  // namespace
}  // namespace modelgen
