// The generated Swevers drive model (drive_torque, drive_torque_jacobian of the compiled-in
// KR150 and TX-40) through the runtime's GeneratedDriveModel adapter equals the runtime's own
// ReferenceDriveModel (numeric reference regressor, eq. 7-10 written in the runtime): same
// parameter names, torques and Jacobians on random states and parameters.

#include <gtest/gtest.h>

#include "generated/kr150/kr150.hpp"
#include "generated/tx40/tx40.hpp"
#include "modelgen/ml/drive_model.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

template <class Model>
void expect_equal_models(const std::string& description_path) {
  const modelgen::RobotModel description =
      modelgen::load_robot(test::source_path(description_path));
  const GeneratedModel<Model> base;  // for the drive chain
  ReferenceDriveModel reference(description.tree, base.drive_chain());
  GeneratedDriveModel<Model> generated;
  ASSERT_EQ(generated.param_names(), reference.param_names()) << description_path;
  const int n = generated.dof(), p = generated.num_params();
  test::Random random(77);
  const int samples = 40;
  Eigen::MatrixXd q(samples, n), dq(samples, n), ddq(samples, n);
  for (int s = 0; s < samples; ++s) {
    q.row(s) = random.vector(n, -2, 2);
    dq.row(s) = random.vector(n, -2, 2);
    ddq.row(s) = random.vector(n, -5, 5);
  }
  generated.set_samples(q, dq, ddq);
  reference.set_samples(q, dq, ddq);
  Eigen::VectorXd theta = random.vector(p, -1, 1);
  for (int k = 0; k < p; ++k) {
    const std::string& name = generated.param_names()[k];
    if (name.rfind("Rz", 0) == 0) theta[k] = random.uniform(0.7, 0.95);  // efficiencies
  }
  Eigen::VectorXd tau1(n), tau2(n);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J1(n, p), J2(n, p);
  for (int s = 0; s < samples; ++s) {
    generated.torque_jacobian(s, theta.data(), tau1.data(), J1.data());
    reference.torque_jacobian(s, theta.data(), tau2.data(), J2.data());
    EXPECT_LT(test::relative_error(tau1, tau2, 1.0), 1e-12) << description_path << " " << s;
    EXPECT_LT((J1 - J2).cwiseAbs().maxCoeff(), 1e-10 * (1 + J2.cwiseAbs().maxCoeff()))
        << description_path << " " << s;
  }
}

TEST(GeneratedDriveModel, Kr150EqualsTheReferenceDriveModel) {
  expect_equal_models<kr150::Model>("robots/kr150.yaml");
}

TEST(GeneratedDriveModel, Tx40EqualsTheReferenceDriveModel) {
  expect_equal_models<tx40::Model>("robots/tx40.yaml");
}

}  // namespace
}  // namespace modelgen
