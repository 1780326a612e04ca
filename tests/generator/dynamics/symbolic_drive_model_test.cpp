// The symbolic Swevers drive model (eq. 7-10) on given rigid-body torques: its parameter list,
// V = K^-1 and its errors, and the DAG's values against eq. 7-10 written out here for the TX-40
// (gear ratios, a motor turning against its joint, coupled axes 5-6) and the KR150 (coupled
// wrist), on both branches of eq. 8 and at the switch.

#include "generator/dynamics/drive_model.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>
#include <Eigen/LU>

#include "modelgen/model/load_robot.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

TEST(DriveModel, ParametersAreTheInertialOnesThenFourPerJoint) {
  ExprGraph g;
  const RobotModel model = load_robot(test::source_path("robots/kr150.yaml"));
  const DriveParameters parameters = make_drive_parameters(g, model.tree);
  // 7 bodies (the flange is fixed) of 10 inertial parameters, then 6 joints of 4.
  ASSERT_EQ(parameters.names.size(), 7u * 10 + 6 * 4);
  EXPECT_EQ(parameters.names[0], "XX1");
  EXPECT_EQ(parameters.names[9], "M1");
  EXPECT_EQ(parameters.names[10], "XX2");
  EXPECT_EQ(parameters.names[69], "M7");
  EXPECT_EQ(parameters.names[70], "JM1");
  EXPECT_EQ(parameters.names[73], "Rz1");
  EXPECT_EQ(parameters.names[93], "Rz6");
  EXPECT_EQ(g.symbols()[g.node(parameters.theta[93]).symbol].name, "theta[93]");
  EXPECT_EQ(parameters.Rz[5], parameters.theta[93]);
  EXPECT_EQ(model.tree.params[parameters.standard_index[10]].name, "XX2");
  // The rigid-body parameter vector: theta where inertial, zero for Ia, Fv, Fc, Iam, ...
  const std::vector<ExprId> p = rigid_body_parameters(g, model.tree, parameters);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const std::string& name = model.tree.params[k].name;
    const bool drive_term = name.rfind("Ia", 0) == 0 || name.rfind("Fv", 0) == 0 ||
                            name.rfind("Fc", 0) == 0 || name.rfind("OFF", 0) == 0;
    EXPECT_EQ(g.is_zero(p[k]), drive_term) << name;
  }
}

TEST(DriveModel, CouplingInverseAndItsErrors) {
  Eigen::MatrixXd K(2, 2);
  K << 45, 0, 32, 32;
  const Eigen::MatrixXd V = joint_from_motor(K, 2);
  EXPECT_LT((K * V - Eigen::MatrixXd::Identity(2, 2)).norm(), 1e-15);
  EXPECT_THROW(joint_from_motor(K, 3), std::logic_error);
  Eigen::MatrixXd singular(2, 2);
  singular << 1, 2, 2, 4;
  EXPECT_THROW(joint_from_motor(singular, 2), std::logic_error);
}

class DriveTorquesOf : public testing::TestWithParam<std::string> {};

TEST_P(DriveTorquesOf, EqualEquations7To10WrittenOut) {
  ExprGraph g;
  const RobotModel model = load_robot(test::source_path(GetParam()));
  const int n = model.dof();
  const SymbolicInputs in = make_symbolic_inputs(g, model.tree);
  const DriveParameters parameters = make_drive_parameters(g, model.tree);
  std::vector<ExprId> tau_G;
  for (int i = 0; i < n; ++i) {
    tau_G.push_back(g.symbol({"tau_G[" + std::to_string(i) + "]", SymbolKind::kInput, ""}));
  }
  const Eigen::MatrixXd& K = model.drives.motor_from_joint;
  const DriveTorques torques = derive_drive_torques(g, K, in, parameters, tau_G);
  ASSERT_EQ(static_cast<int>(torques.tau_M.size()), n);

  test::Random random(77);
  int driving = 0, driven = 0, switched = 0;
  for (int s = 0; s < 300; ++s) {
    std::map<std::string, double> values;
    Eigen::VectorXd dq = random.vector(n, -2, 2), ddq = random.vector(n, -5, 5);
    Eigen::VectorXd tG = random.vector(n, -100, 100);
    if (s % 10 == 0) dq.setZero();  // the switch of eq. 8 on every joint
    Eigen::VectorXd theta = random.vector(static_cast<int>(parameters.theta.size()), 0.1, 2);
    for (int i = 0; i < n; ++i)
      theta[parameters.theta.size() - 4 * n + 4 * i + 3] = random.uniform(0.5, 0.99);
    const auto leaf = [&](const Symbol& symbol) {
      const std::string& text = symbol.kind == SymbolKind::kInput ? symbol.name : symbol.input;
      const std::size_t open = text.find('[');
      const std::string array = text.substr(0, open);
      const int index = std::stoi(text.substr(open + 1));
      const double x = array == "dq"      ? dq[index]
                       : array == "ddq"   ? ddq[index]
                       : array == "tau_G" ? tG[index]
                       : array == "theta" ? theta[index]
                                          : 0.0;
      if (symbol.kind == SymbolKind::kSign) return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0);
      return x;
    };
    const std::vector<double> value = g.evaluate(leaf);
    // Eq. 10, 9, 8 (branches as written), 7.
    const Eigen::VectorXd tau_out = K.transpose().lu().solve(tG);
    const Eigen::VectorXd dq_M = K * dq, ddq_M = K * ddq;
    for (int i = 0; i < n; ++i) {
      const Eigen::Index at = theta.size() - 4 * n + 4 * i;
      const double JM = theta[at], Rv = theta[at + 1], Rc = theta[at + 2], Rz = theta[at + 3];
      const double power = tau_out[i] * dq_M[i];
      double tau_T = (tau_out[i] / Rz + tau_out[i] * Rz) / 2;
      if (power > 0) {
        tau_T = tau_out[i] / Rz;
        ++driving;
      } else if (power < 0) {
        tau_T = tau_out[i] * Rz;
        ++driven;
      } else {
        ++switched;
      }
      const double sign = dq_M[i] > 0 ? 1 : (dq_M[i] < 0 ? -1 : 0);
      const double expected = tau_T + JM * ddq_M[i] + Rv * dq_M[i] + Rc * sign;
      EXPECT_NEAR(value[torques.tau_M[i]], expected, 1e-12 * (1 + std::abs(expected)))
          << "joint " << i + 1 << ", sample " << s;
      EXPECT_NEAR(value[torques.tau_out[i]], tau_out[i], 1e-12 * (1 + std::abs(tau_out[i])));
    }
  }
  EXPECT_GT(driving, 100);
  EXPECT_GT(driven, 100);
  EXPECT_EQ(switched, 30 * n);
}

INSTANTIATE_TEST_SUITE_P(CoupledRobots, DriveTorquesOf,
                         testing::Values("robots/kr150.yaml", "robots/tx40.yaml"),
                         test::robot_test_name);

}  // namespace
}  // namespace modelgen::gen
