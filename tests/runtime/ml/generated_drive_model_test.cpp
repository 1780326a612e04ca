// The generated Swevers drive model of every shipped robot (drive_regressor once per sample,
// then drive_torque_given_regressor and drive_torque_jacobian_given_regressor) through the
// runtime's GeneratedDriveModel adapter equals the runtime's own ReferenceDriveModel (numeric
// reference regressor, eq. 7-10 written in the runtime) and its ceres::Jet derivatives: same
// parameter names, torques and Jacobians on random states and parameters, every torque written
// (NaN-filled buffers), the Jacobian into one array zeroed once as the interface asks (its
// always-zero entries are never written), also for samples bound again.

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "generated/comau_smart_six/comau_smart_six.hpp"
#include "generated/franka_panda/franka_panda.hpp"
#include "generated/kr150/kr150.hpp"
#include "generated/kuka_iiwa14_drake/kuka_iiwa14_drake.hpp"
#include "generated/kuka_kr150_2/kuka_kr150_2.hpp"
#include "generated/panda_arm/panda_arm.hpp"
#include "generated/tx40/tx40.hpp"
#include "generated/ur5/ur5.hpp"
#include "modelgen/ml/drive_model.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Samples {
  Eigen::MatrixXd q, dq, ddq;
};

Samples random_samples(test::Random& random, int count, int n) {
  Samples x{Eigen::MatrixXd(count, n), Eigen::MatrixXd(count, n), Eigen::MatrixXd(count, n)};
  for (int s = 0; s < count; ++s) {
    x.q.row(s) = random.vector(n, -2, 2);
    x.dq.row(s) = random.vector(n, -2, 2);
    x.ddq.row(s) = random.vector(n, -5, 5);
  }
  return x;
}

template <class Model>
void expect_equal_models(const std::string& description_path) {
  constexpr int P = Model::kDriveParams;
  using Jet = ceres::Jet<double, P>;
  const RobotModel description = load_robot(test::source_path(description_path));
  const GeneratedModel<Model> base;  // for the drive chain
  ReferenceDriveModel reference(description.tree, base.drive_chain());
  GeneratedDriveModel<Model> generated;
  ASSERT_EQ(generated.param_names(), reference.param_names()) << description_path;
  const int n = generated.dof();
  ASSERT_EQ(generated.num_params(), P);
  test::Random random(77);
  const int samples = 40;
  // Bound twice: the second binding (other samples, fewer) must replace the first entirely.
  const Samples first = random_samples(random, samples + 7, n);
  generated.set_samples(first.q, first.dq, first.ddq);
  const Samples x = random_samples(random, samples, n);
  generated.set_samples(x.q, x.dq, x.ddq);
  reference.set_samples(x.q, x.dq, x.ddq);
  ASSERT_EQ(generated.num_samples(), samples);
  double worst_tau = 0, worst_J = 0, worst_jet = 0;
  RowMajor J1 = RowMajor::Zero(n, P);  // zeroed once, reused for every sample and trial
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd theta = random.vector(P, -1, 1);
    for (int k = 0; k < P; ++k) {
      const std::string& name = generated.param_names()[k];
      if (name.rfind("Rz", 0) == 0) theta[k] = random.uniform(0.7, 0.95);  // efficiencies
    }
    std::vector<Jet> theta_jet(P), tau_jet(n);
    for (int k = 0; k < P; ++k) theta_jet[k] = Jet(theta[k], k);
    for (int s = 0; s < samples; ++s) {
      Eigen::VectorXd tau1 = Eigen::VectorXd::Constant(n, std::nan("")), tau2(n), tau3(n);
      tau3 = tau1;
      RowMajor J2(n, P);
      generated.torque_jacobian(s, theta.data(), tau1.data(), J1.data());
      generated.torque(s, theta.data(), tau3.data());
      reference.torque_jacobian(s, theta.data(), tau2.data(), J2.data());
      reference.evaluate(s, theta_jet.data(), tau_jet.data());
      ASSERT_TRUE(J1.allFinite() && tau1.allFinite() && tau3.allFinite())
          << description_path << " sample " << s << ": an output entry is not written";
      RowMajor J_jet(n, P);
      Eigen::VectorXd tau_value(n);
      for (int i = 0; i < n; ++i) {
        J_jet.row(i) = tau_jet[i].v.transpose();
        tau_value[i] = tau_jet[i].a;
      }
      const double scale = 1 + J2.cwiseAbs().maxCoeff();
      worst_tau = std::max({worst_tau, test::relative_error(tau1, tau2, 1.0),
                            test::relative_error(tau3, tau2, 1.0),
                            test::relative_error(tau1, tau_value, 1.0)});
      worst_J = std::max(worst_J, (J1 - J2).cwiseAbs().maxCoeff() / scale);
      worst_jet = std::max(worst_jet, (J1 - J_jet).cwiseAbs().maxCoeff() / scale);
    }
  }
  EXPECT_LT(worst_tau, 1e-12) << description_path;
  EXPECT_LT(worst_J, 1e-12) << description_path;
  EXPECT_LT(worst_jet, 1e-12) << description_path;
}

TEST(GeneratedDriveModel, Kr150EqualsTheReferenceDriveModel) {
  expect_equal_models<kr150::Model>("robots/kr150.yaml");
}

TEST(GeneratedDriveModel, Tx40EqualsTheReferenceDriveModel) {
  expect_equal_models<tx40::Model>("robots/tx40.yaml");
}

TEST(GeneratedDriveModel, ComauSmartSixEqualsTheReferenceDriveModel) {
  expect_equal_models<comau_smart_six::Model>("robots/comau_smart_six.yaml");
}

TEST(GeneratedDriveModel, PandaArmEqualsTheReferenceDriveModel) {
  expect_equal_models<panda_arm::Model>("robots/panda_arm.yaml");
}

TEST(GeneratedDriveModel, Ur5EqualsTheReferenceDriveModel) {
  expect_equal_models<ur5::Model>("robots/urdf/ur5.urdf");
}

TEST(GeneratedDriveModel, Iiwa14EqualsTheReferenceDriveModel) {
  expect_equal_models<iiwa14::Model>("robots/urdf/kuka_iiwa14_drake.urdf");
}

TEST(GeneratedDriveModel, FrankaPandaEqualsTheReferenceDriveModel) {
  expect_equal_models<panda::Model>("robots/urdf/franka_panda.urdf");
}

TEST(GeneratedDriveModel, KukaKr150UrdfEqualsTheReferenceDriveModel) {
  expect_equal_models<kuka_kr150_2::Model>("robots/urdf/kuka_kr150_2.urdf");
}

}  // namespace
}  // namespace modelgen
