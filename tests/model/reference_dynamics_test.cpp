// The numeric reference against independent facts: closed-form dynamics of a planar 2R arm and
// of a prismatic lift, linearity in the standard parameters (W p == RNE), and the power balance
// dq . tau == dE/dt along smooth trajectories (energy from a separate code path).

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "runtime/model/mdh_yaml_loader.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using modelgen::RobotModel;

Eigen::VectorXd parameters(const RobotModel& model,
                           const std::vector<std::pair<std::string, double>>& values) {
  Eigen::VectorXd p = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(model.tree.params.size()));
  for (const auto& [name, value] : values) {
    const int k = model.param_index(name);
    EXPECT_GE(k, 0) << name;
    if (k >= 0) p[k] = value;
  }
  return p;
}

TEST(ReferenceDynamics, PlanarTwoLinkArmMatchesClosedForm) {
  // Two parallel revolute axes along z, link lengths L1 along x1; gravity in the plane (-y).
  const RobotModel model = modelgen::load_mdh_yaml(
      "planar.yaml",
      "name: planar\n"
      "gravity: [0, -9.81, 0]\n"
      "joints:\n"
      "  - {type: revolute, alpha: 0, d: 0, theta: 0, r: 0}\n"
      "  - {type: revolute, alpha: 0, d: 0.7, theta: 0, r: 0}\n");
  const double L1 = 0.7, m1 = 3.0, a1 = 0.4, m2 = 2.0, a2 = 0.25, g = 9.81;
  const double Ia1 = 0.2, Fv2 = 0.3, Fc2 = 0.5, off1 = 0.1;
  // Point masses on the x axes: MX = m a, YY = ZZ = m a^2.
  const Eigen::VectorXd p = parameters(
      model, {{"MX1", m1 * a1}, {"M1", m1}, {"YY1", m1 * a1 * a1}, {"ZZ1", m1 * a1 * a1},
              {"MX2", m2 * a2}, {"M2", m2}, {"YY2", m2 * a2 * a2}, {"ZZ2", m2 * a2 * a2},
              {"Ia1", Ia1}, {"Fv2", Fv2}, {"Fc2", Fc2}, {"OFF1", off1}});
  const ReferenceDynamics dynamics(model.tree);
  test::Random random(11);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::VectorXd q = random.vector(2, -3, 3), dq = random.vector(2, -2, 2),
                          ddq = random.vector(2, -5, 5);
    const double c2 = std::cos(q[1]), s2 = std::sin(q[1]);
    const double c1 = std::cos(q[0]), c12 = std::cos(q[0] + q[1]);
    // Textbook Lagrange equations of the 2R arm with point masses.
    const double M11 = m1 * a1 * a1 + m2 * (L1 * L1 + a2 * a2 + 2 * L1 * a2 * c2);
    const double M12 = m2 * (a2 * a2 + L1 * a2 * c2);
    const double M22 = m2 * a2 * a2;
    const double h = m2 * L1 * a2 * s2;
    Eigen::Vector2d expected;
    expected[0] = M11 * ddq[0] + M12 * ddq[1] - h * (2 * dq[0] * dq[1] + dq[1] * dq[1]) +
                  (m1 * a1 + m2 * L1) * g * c1 + m2 * a2 * g * c12 + Ia1 * ddq[0] + off1;
    expected[1] = M12 * ddq[0] + M22 * ddq[1] + h * dq[0] * dq[0] + m2 * a2 * g * c12 +
                  Fv2 * dq[1] + Fc2 * (dq[1] > 0 ? 1 : -1);
    EXPECT_LT(test::relative_error(dynamics.inverse_dynamics(q, dq, ddq, p), expected), 1e-12);
  }
}

TEST(ReferenceDynamics, PrismaticLiftMatchesClosedForm) {
  // A vertical prismatic joint at radius d on a vertical revolute base, carrying a point mass
  // at its frame origin plus a rotational inertia ZZ2 about z2. The radius never changes, so:
  // tau1 = (m2 d^2 + ZZ2) ddq1 and tau2 = m2 (ddq2 + g).
  const RobotModel model = modelgen::load_mdh_yaml(
      "lift.yaml",
      "name: lift\n"
      "joints:\n"
      "  - {type: revolute, alpha: 0, d: 0, theta: 0, r: 0}\n"
      "  - {type: prismatic, alpha: 0, d: 0.5, theta: 0, r: 0}\n");
  const double m2 = 4.0, d = 0.5, g = 9.81;
  const Eigen::VectorXd p = parameters(model, {{"M2", m2}, {"ZZ2", m2 * d * d}});
  const ReferenceDynamics dynamics(model.tree);
  test::Random random(5);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::VectorXd q = random.vector(2, -1, 1), dq = random.vector(2, -2, 2),
                          ddq = random.vector(2, -5, 5);
    Eigen::Vector2d expected(ddq[0] * (m2 * d * d + m2 * d * d), m2 * (ddq[1] + g));
    EXPECT_LT(test::relative_error(dynamics.inverse_dynamics(q, dq, ddq, p), expected), 1e-12);
  }
}

class ShippedRobot : public testing::TestWithParam<std::string> {};

TEST_P(ShippedRobot, RegressorTimesParametersIsInverseDynamics) {
  const RobotModel model = modelgen::load_robot(GetParam());
  const ReferenceDynamics dynamics(model.tree);
  test::Random random(1);
  const int n = dynamics.dof();
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::VectorXd q = random.vector(n, -3, 3), dq = random.vector(n, -2, 2),
                          ddq = random.vector(n, -5, 5), p = random.vector(dynamics.num_params(), -1, 1);
    const Eigen::MatrixXd W = dynamics.standard_regressor(q, dq, ddq);
    ASSERT_EQ(W.rows(), n);
    ASSERT_EQ(W.cols(), dynamics.num_params());
    EXPECT_LT(test::relative_error(W * p, dynamics.inverse_dynamics(q, dq, ddq, p)), 1e-12);
  }
}

TEST_P(ShippedRobot, PowerEqualsTimeDerivativeOfEnergy) {
  const RobotModel model = modelgen::load_robot(GetParam());
  const ReferenceDynamics dynamics(model.tree);
  const int n = dynamics.dof();
  test::Random random(3);
  // Random link inertials and drive inertia; friction and offset dissipate or inject power
  // outside the energy balance, so they stay zero.
  Eigen::VectorXd p = random.vector(dynamics.num_params(), -1, 1);
  for (int k = 0; k < dynamics.num_params(); ++k) {
    const ParamKind kind = model.tree.params[k].kind;
    if (kind == ParamKind::kIa || kind == ParamKind::kIam || kind == ParamKind::kM) {
      p[k] = std::abs(p[k]) + 0.1;
    }
    if (kind == ParamKind::kFv || kind == ParamKind::kFc || kind == ParamKind::kOff ||
        kind == ParamKind::kFvm || kind == ParamKind::kFcm || kind == ParamKind::kFvPos ||
        kind == ParamKind::kFvNeg || kind == ParamKind::kFcPos || kind == ParamKind::kFcNeg) {
      p[k] = 0;
    }
  }
  // q(t) = a sin(w t + phi): smooth, with analytic dq and ddq.
  const Eigen::VectorXd a = random.vector(n, 0.2, 1.0), w = random.vector(n, 0.5, 2.0),
                        phi = random.vector(n, 0, 6.28);
  auto state = [&](double t, Eigen::VectorXd& q, Eigen::VectorXd& dq, Eigen::VectorXd& ddq) {
    q = (a.array() * (w.array() * t + phi.array()).sin()).matrix();
    dq = (a.array() * w.array() * (w.array() * t + phi.array()).cos()).matrix();
    ddq = (-w.array().square() * q.array()).matrix();
  };
  auto energy = [&](double t) {
    Eigen::VectorXd q, dq, ddq;
    state(t, q, dq, ddq);
    return dynamics.kinetic_energy(q, dq, p) + dynamics.potential_energy(q, p);
  };
  const double h = 1e-4;
  for (double t = 0; t < 3; t += 0.37) {
    Eigen::VectorXd q, dq, ddq;
    state(t, q, dq, ddq);
    const double power = dq.dot(dynamics.inverse_dynamics(q, dq, ddq, p));
    // Fourth-order central difference: truncation error ~ h^4.
    const double dE = (-energy(t + 2 * h) + 8 * energy(t + h) - 8 * energy(t - h) + energy(t - 2 * h)) / (12 * h);
    EXPECT_NEAR(power, dE, 1e-7 * std::max(1.0, std::abs(power))) << "t = " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(All, ShippedRobot, testing::ValuesIn(test::shipped_robots()), test::robot_test_name);

}  // namespace
}  // namespace modelgen
