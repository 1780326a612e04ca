// The symbolic power model, evaluated through the DAG, against the numeric reference on every
// shipped robot: h p equals the reference kinetic plus potential energy, and dh p equals the
// power dq . tau of the reference inverse dynamics, friction included (Gautier & Briot eq. 9).

#include <cmath>

#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "generator/dynamics/power_model.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/symbol_values.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

class PowerModel : public testing::TestWithParam<std::string> {};

TEST_P(PowerModel, EnergyAndPowerMatchTheReference) {
  const RobotModel model = load_robot(GetParam());
  const ReferenceDynamics reference(model.tree);
  ExprGraph graph;
  const SymbolicInputs in = make_symbolic_inputs(graph, model.tree);
  const std::vector<ExprId> h = derive_energy_regressor(graph, model.tree, in);
  const std::vector<ExprId> dh = derive_power_regressor(graph, model.tree, in, h);
  const int n = model.dof(), np = reference.num_params();
  test::Random random(8);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::VectorXd q = random.vector(n, -3, 3), dq = random.vector(n, -2, 2),
                          ddq = random.vector(n, -5, 5), p = random.vector(np, -1, 1);
    const std::vector<double> value = graph.evaluate(test::symbol_values(q, dq, ddq, p));
    double energy = 0, power = 0;
    for (int k = 0; k < np; ++k) {
      energy += value[h[k]] * p[k];
      power += value[dh[k]] * p[k];
    }
    const double expected_energy = reference.kinetic_energy(q, dq, p) + reference.potential_energy(q, p);
    const double expected_power = dq.dot(reference.inverse_dynamics(q, dq, ddq, p));
    EXPECT_NEAR(energy, expected_energy, 1e-11 * std::max(1.0, std::abs(expected_energy)));
    EXPECT_NEAR(power, expected_power, 1e-11 * std::max(1.0, std::abs(expected_power)));
  }
}

INSTANTIATE_TEST_SUITE_P(All, PowerModel, testing::ValuesIn(test::shipped_robots()), test::robot_test_name);

}  // namespace
}  // namespace modelgen::gen
