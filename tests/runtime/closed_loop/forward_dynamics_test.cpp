// Forward dynamics against Orocos KDL: the accelerations computed for random torques, fed to
// KDL's recursive Newton-Euler (plus the drive terms), give the torques back; the generated
// mass matrix equals the one built from the reference's inverse dynamics, and, for the rigid
// bodies alone, KDL's mass matrix and forward dynamics; impossible parameters are refused.

#include "modelgen/closed_loop/forward_dynamics.hpp"

#include <cmath>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

struct Case {
  const char* name;
  const char* description;
};

// The shipped robots KDL can take as a chain (the franka_panda URDF's two fingers make a tree:
// its mass matrix is compared with the reference in tests/generated), generated code compiled
// in; the TX-40 and KR150 with coupled wrist drives.
const Case kCases[] = {{"tx40", "robots/tx40.yaml"},
                       {"kr150", "robots/kr150.yaml"},
                       {"ur5", "robots/urdf/ur5.urdf"},
                       {"iiwa14", "robots/urdf/kuka_iiwa14_drake.urdf"},
                       {"kuka_kr150_2", "robots/urdf/kuka_kr150_2.urdf"},
                       {"panda_arm", "robots/panda_arm.yaml"},
                       {"comau_smart_six", "robots/comau_smart_six.yaml"}};

std::vector<double> base_of(const IdentificationModel& model, const Eigen::VectorXd& p) {
  std::vector<double> beta(model.num_base_params());
  model.base_from_standard(p.data(), beta.data());
  return beta;
}

TEST(ForwardDynamics, KdlInverseDynamicsOfTheAccelerationsGivesTheTorquesBack) {
  for (const Case& c : kCases) {
    const RobotModel description = load_robot(test::source_path(c.description));
    ASSERT_TRUE(test::is_serial(description.tree)) << c.name;
    const std::unique_ptr<IdentificationModel> generated = internal::make_shipped_model(c.name);
    ASSERT_NE(generated, nullptr) << c.name;
    const ReferenceModel reference(description.name, description.tree);
    test::Random random(13);
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
      const test::JointState state = test::random_state(description, random);
      const int n = generated->dof();
      const Eigen::VectorXd tau = random.vector(n, -50, 50);
      const IdentificationModel* models[] = {generated.get(), &reference};
      for (const IdentificationModel* model : models) {
        ForwardDynamics plant(*model, base_of(*model, p));
        Eigen::VectorXd ddq(n);
        plant.accelerations(state.q.data(), state.dq.data(), tau.data(), ddq.data());
        const Eigen::VectorXd back =
            test::kdl_inverse_dynamics(description.tree, state.q, state.dq, ddq, p);
        EXPECT_LT((back - tau).norm(), 1e-9 * (1 + tau.norm()))
            << c.name << " (" << (model == generated.get() ? "generated" : "reference")
            << "), trial " << trial << ": tau " << tau.transpose() << ", back "
            << back.transpose();
      }
    }
  }
}

TEST(ForwardDynamics, GeneratedMassMatrixEqualsTheReferencesColumns) {
  for (const Case& c : kCases) {
    const RobotModel description = load_robot(test::source_path(c.description));
    const std::unique_ptr<IdentificationModel> generated = internal::make_shipped_model(c.name);
    const ReferenceModel reference(description.name, description.tree);
    test::Random random(5);
    const int n = generated->dof();
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
      const Eigen::VectorXd q = random.vector(n, -3, 3);
      Eigen::MatrixXd M1(n, n), M2(n, n);
      generated->mass_matrix(q.data(), base_of(*generated, p).data(), M1.data());
      reference.mass_matrix(q.data(), base_of(reference, p).data(), M2.data());
      EXPECT_LT((M1 - M2).norm(), 1e-10 * M2.norm()) << c.name;
      EXPECT_LT((M1 - M1.transpose()).norm(), 1e-12 * M1.norm()) << c.name;
    }
  }
}

// KDL has no drive model: with the drive parameters (rotor inertias, friction, offsets) at zero,
// the generated mass matrix is KDL's ChainDynParam's and the accelerations are KDL's
// ChainFdSolver_RNE's (an articulated-body algorithm, independent of M and its factorisation).
TEST(ForwardDynamics, RigidBodiesAloneEqualKdlMassMatrixAndForwardDynamics) {
  for (const Case& c : kCases) {
    const RobotModel description = load_robot(test::source_path(c.description));
    const std::unique_ptr<IdentificationModel> generated = internal::make_shipped_model(c.name);
    ASSERT_NE(generated, nullptr) << c.name;
    const int n = generated->dof();
    test::Random random(28);
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
      for (std::size_t k = 0; k < description.tree.params.size(); ++k) {
        if (!is_inertial(description.tree.params[k].kind)) p[k] = 0.0;
      }
      const test::JointState state = test::random_state(description, random);
      const Eigen::VectorXd tau = random.vector(n, -50, 50);
      Eigen::MatrixXd M(n, n);
      generated->mass_matrix(state.q.data(), base_of(*generated, p).data(), M.data());
      const Eigen::MatrixXd M_kdl = test::kdl_rigid_body_mass_matrix(description.tree, state.q, p);
      EXPECT_LT((M - M_kdl).norm(), 1e-10 * M_kdl.norm()) << c.name << ", trial " << trial;
      ForwardDynamics plant(*generated, base_of(*generated, p));
      Eigen::VectorXd ddq(n);
      plant.accelerations(state.q.data(), state.dq.data(), tau.data(), ddq.data());
      const Eigen::VectorXd ddq_kdl =
          test::kdl_rigid_body_forward_dynamics(description.tree, state.q, state.dq, tau, p);
      EXPECT_LT((ddq - ddq_kdl).norm(), 1e-8 * (1 + ddq_kdl.norm()))
          << c.name << ", trial " << trial << ": " << ddq.transpose() << " vs KDL "
          << ddq_kdl.transpose();
    }
  }
}

TEST(ForwardDynamics, ImpossibleParametersAndWrongSizesAreRefused) {
  const std::unique_ptr<IdentificationModel> tx40 = internal::make_shipped_model("tx40");
  const int n = tx40->dof();
  EXPECT_THROW(ForwardDynamics(*tx40, std::vector<double>(3, 1.0)), std::invalid_argument);
  // All base parameters zero: no inertia at all, M = 0.
  ForwardDynamics massless(*tx40, std::vector<double>(tx40->num_base_params(), 0.0));
  const std::vector<double> q(n, 0.1), dq(n, 0.0), tau(n, 1.0);
  std::vector<double> ddq(n);
  try {
    massless.accelerations(q.data(), dq.data(), tau.data(), ddq.data());
    FAIL() << "a zero mass matrix was solved";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("not positive definite at q = [0.1, 0.1"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace modelgen
