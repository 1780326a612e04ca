// The symbolic power model, evaluated through the DAG, against the numeric reference on every
// shipped robot: h p equals the reference kinetic plus potential energy, and dh p equals the
// power dq . tau of the reference inverse dynamics, friction included (Gautier & Briot eq. 9).

#include <cmath>

#include <gtest/gtest.h>

#include "generator/description/load_robot.hpp"
#include "generator/dynamics/power_model.hpp"
#include "modelgen/reference_dynamics.hpp"
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
    const std::vector<double> value = graph.evaluate([&](const Symbol& s) {
      auto input = [&](const std::string& text) {
        const std::size_t open = text.find('[');
        const int index = std::stoi(text.substr(open + 1));
        const std::string array = text.substr(0, open);
        return array == "q" ? q[index] : array == "dq" ? dq[index] : array == "ddq" ? ddq[index] : p[index];
      };
      switch (s.kind) {
        case SymbolKind::kInput: return input(s.name);
        case SymbolKind::kSin: return std::sin(input(s.input));
        case SymbolKind::kCos: return std::cos(input(s.input));
        case SymbolKind::kSign: return input(s.input) > 0 ? 1.0 : (input(s.input) < 0 ? -1.0 : 0.0);
        case SymbolKind::kPositive: return input(s.input) > 0 ? 1.0 : 0.0;
        case SymbolKind::kNegative: return input(s.input) < 0 ? 1.0 : 0.0;
      }
      return 0.0;
    });
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

std::string robot_test_name(const testing::TestParamInfo<std::string>& info) {
  std::string name = info.param.substr(info.param.find_last_of('/') + 1);
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(All, PowerModel, testing::ValuesIn(test::shipped_robots()), robot_test_name);

}  // namespace
}  // namespace modelgen::gen
