// ml_joint_errors (issue 31): the ML route's motor torque errors on the joint side, against
// sums written out by hand for a coupled drive chain, the joints an omitted motor leaves
// incomplete, and the round trip through ml_experiment's own tau_M = K^-T tau on the KR150's
// coupled wrist (the ML residual mapped back is the joint torque minus K^T times the model).

#include "modelgen/ml/joint_errors.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <vector>

#include <Eigen/Dense>

#include "modelgen/ml/problem.hpp"
#include "modelgen/signal/prepare.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

// dq_M = K dq: motor 4 turns with joints 3 and 4 (a coupled pair), the others alone.
Eigen::MatrixXd coupled_k() {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(4, 4);
  K(0, 0) = 2;
  K(1, 1) = 3;
  K(2, 2) = 1.5;
  K(3, 2) = -0.7;
  K(3, 3) = 1.2;
  return K;
}

TEST(MlJointErrors, SumsOfTheMotorsThatDriveEachJoint) {
  test::Random random(31);
  Eigen::MatrixXd e(5, 4);
  for (Eigen::Index s = 0; s < 5; ++s) {
    for (int i = 0; i < 4; ++i) e(s, i) = random.uniform(-10, 10);
  }
  const MlJointErrors out = ml_joint_errors(e, coupled_k(), {0, 1, 2, 3}, {3, 2});
  ASSERT_EQ(out.errors.size(), 2u);
  ASSERT_EQ(out.errors[0].rows(), 3);
  ASSERT_EQ(out.errors[1].rows(), 2);
  for (Eigen::Index s = 0; s < 5; ++s) {
    const Eigen::MatrixXd& block = s < 3 ? out.errors[0] : out.errors[1];
    const Eigen::Index r = s < 3 ? s : s - 3;
    // tau_joint = K^T tau_M, column by column of K written out.
    EXPECT_NEAR(block(r, 0), 2 * e(s, 0), 1e-12);
    EXPECT_NEAR(block(r, 1), 3 * e(s, 1), 1e-12);
    EXPECT_NEAR(block(r, 2), 1.5 * e(s, 2) - 0.7 * e(s, 3), 1e-12);
    EXPECT_NEAR(block(r, 3), 1.2 * e(s, 3), 1e-12);
  }
  EXPECT_EQ(out.judged, std::vector<bool>({true, true, true, true}));
}

TEST(MlJointErrors, AnOmittedMotorLeavesItsJointsUnjudged) {
  const Eigen::MatrixXd e = Eigen::MatrixXd::Ones(2, 4);
  // Motor 1 alone drives joint 1.
  EXPECT_EQ(ml_joint_errors(e, coupled_k(), {1, 2, 3}, {2}).judged,
            std::vector<bool>({false, true, true, true}));
  // Motor 4 drives joints 3 and 4.
  EXPECT_EQ(ml_joint_errors(e, coupled_k(), {0, 1, 2}, {2}).judged,
            std::vector<bool>({true, true, false, false}));
  // Motor 3 drives joint 3 only (joint 4 does not move it).
  EXPECT_EQ(ml_joint_errors(e, coupled_k(), {0, 1, 3}, {2}).judged,
            std::vector<bool>({true, true, false, true}));
}

TEST(MlJointErrors, WrongSizesAreRefused) {
  const Eigen::MatrixXd e = Eigen::MatrixXd::Ones(4, 4);
  EXPECT_THROW(ml_joint_errors(e, coupled_k(), {0}, {3}), std::invalid_argument);
  EXPECT_THROW(ml_joint_errors(e, coupled_k(), {4}, {4}), std::invalid_argument);
  EXPECT_THROW(ml_joint_errors(Eigen::MatrixXd::Ones(4, 3), coupled_k(), {0}, {4}),
               std::invalid_argument);
}

// The ML fit compares tau_M = K^-T tau (ml_experiment) with the model's motor torques F; mapped
// back, its error must be the record's joint torque minus K^T F.
TEST(MlJointErrors, TheMlResidualMappedBackIsTheJointTorqueError) {
  const std::unique_ptr<IdentificationModel> model = internal::make_shipped_model("kr150");
  const DriveChain& drive = model->drive_chain();
  const Eigen::MatrixXd& K = drive.motor_from_joint;
  ASSERT_NE(K(4, 3), 0);  // the coupled wrist: a joint's error mixes motors
  test::Random random(7);
  const Eigen::Index n = 6, samples = 8;
  PreparedExperiment prepared;
  prepared.data.source = "random";
  prepared.data.t = Eigen::VectorXd::LinSpaced(samples, 0, 0.7);
  prepared.data.q = prepared.data.dq = prepared.data.ddq = Eigen::MatrixXd::Zero(samples, n);
  prepared.data.tau.resize(samples, n);
  Eigen::MatrixXd F(samples, n);  // some model's motor torques
  for (Eigen::Index s = 0; s < samples; ++s) {
    for (Eigen::Index j = 0; j < n; ++j) {
      prepared.data.tau(s, j) = random.uniform(-500, 500);
      F(s, j) = random.uniform(-500, 500);
    }
  }
  prepared.tau_noise_variance = Eigen::VectorXd::Ones(n);
  const MlExperiment experiment = ml_experiment(prepared, drive);
  const MlJointErrors out = ml_joint_errors(experiment.tau_M - F, K, {0, 1, 2, 3, 4, 5}, {samples});
  for (Eigen::Index s = 0; s < samples; ++s) {
    for (Eigen::Index j = 0; j < n; ++j) {
      double modelled = 0;  // (K^T F)_j, summed here
      for (Eigen::Index i = 0; i < n; ++i) modelled += K(i, j) * F(s, i);
      EXPECT_NEAR(out.errors[0](s, j), prepared.data.tau(s, j) - modelled, 1e-9) << s << " " << j;
    }
  }
}

}  // namespace
}  // namespace modelgen
