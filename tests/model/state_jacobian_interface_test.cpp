// IdentificationModel::inverse_dynamics_state_jacobian: every compiled-in generated model (its
// generated function) against the numeric reference built from the same description (the
// interface's default, central differences of the reference's inverse dynamics), on random
// states whose joint and motor velocities stay away from the Coulomb friction jumps.

#include <cmath>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Case {
  const char* name;
  const char* description;
};

// Joint velocities in [-2, 2] with every joint and motor velocity at least 0.05 from zero
// (the difference steps, 6e-6 max(1, |dq|), never cross a sign change).
Eigen::VectorXd velocity_away_from_zero(const Eigen::MatrixXd& K, test::Random& random) {
  const int n = static_cast<int>(K.rows());
  for (;;) {
    const Eigen::VectorXd dq = random.vector(n, -2, 2);
    const Eigen::VectorXd motor = K * dq;
    if (dq.cwiseAbs().minCoeff() >= 0.05 && motor.cwiseAbs().minCoeff() >= 0.05) return dq;
  }
}

TEST(StateJacobian, GeneratedEqualsDifferencesOfTheReference) {
  const Case cases[] = {{"tx40", "robots/tx40.yaml"},
                        {"kr150", "robots/kr150.yaml"},
                        {"ur5", "robots/urdf/ur5.urdf"},
                        {"panda_arm", "robots/panda_arm.yaml"}};
  for (const Case& c : cases) {
    const std::unique_ptr<IdentificationModel> generated = internal::make_shipped_model(c.name);
    ASSERT_NE(generated, nullptr) << c.name;
    const RobotModel description = load_robot(test::source_path(c.description));
    const ReferenceModel reference(description.name, description.tree);
    const int n = generated->dof(), nb = generated->num_base_params();
    const Eigen::MatrixXd K = generated->drive_chain().motor_from_joint;
    test::Random random(13);
    std::vector<double> beta(nb);
    RowMajor J_generated(n, 3 * n), J_reference(n, 3 * n);
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::VectorXd q = random.vector(n, -3, 3), dq = velocity_away_from_zero(K, random),
                            ddq = random.vector(n, -5, 5);
      const Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
      reference.base_from_standard(p.data(), beta.data());
      generated->inverse_dynamics_state_jacobian(q.data(), dq.data(), ddq.data(), beta.data(),
                                                 J_generated.data());
      reference.inverse_dynamics_state_jacobian(q.data(), dq.data(), ddq.data(), beta.data(),
                                                J_reference.data());
      // Central differences with h ~ 6e-6: truncation and round-off near 1e-10 of the scale.
      const double scale = J_reference.cwiseAbs().maxCoeff();
      EXPECT_LT((J_generated - J_reference).cwiseAbs().maxCoeff(), 1e-7 * scale)
          << c.name << " trial " << trial;
      // Linear in beta: twice beta, twice the Jacobian.
      std::vector<double> twice(beta);
      for (double& b : twice) b *= 2;
      RowMajor J_twice(n, 3 * n);
      generated->inverse_dynamics_state_jacobian(q.data(), dq.data(), ddq.data(), twice.data(),
                                                 J_twice.data());
      EXPECT_LT((J_twice - 2 * J_generated).cwiseAbs().maxCoeff(), 1e-12 * scale) << c.name;
    }
  }
}

}  // namespace
}  // namespace modelgen
