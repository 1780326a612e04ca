// The symbolic Newton-Euler, evaluated numerically through the DAG, against the numeric
// reference (which keeps the cross-product form the symbolic one replaces with Khalil's U) on
// every shipped robot and on a tree with a prismatic joint inside it: the standard regressor
// column by column and the inverse dynamics with symbolic parameters.

#include <cmath>

#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "generator/dynamics/newton_euler.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "runtime/model/mdh_yaml_loader.hpp"
#include "tests/support/symbol_values.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::gen {
namespace {

void expect_matches_reference(const RobotModel& model) {
  const ReferenceDynamics reference(model.tree);
  ExprGraph graph;
  const SymbolicInputs in = make_symbolic_inputs(graph, model.tree);
  const std::vector<ExprId> W = derive_standard_regressor(graph, model.tree, in);
  const std::vector<ExprId> tau = derive_inverse_dynamics(graph, model.tree, in);
  const int n = model.dof(), np = reference.num_params();
  test::Random random(42);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::VectorXd q = random.vector(n, -3, 3), dq = random.vector(n, -2, 2),
                          ddq = random.vector(n, -5, 5), p = random.vector(np, -1, 1);
    const std::vector<double> value = graph.evaluate(test::symbol_values(q, dq, ddq, p));
    Eigen::MatrixXd W_symbolic(n, np);
    Eigen::VectorXd tau_symbolic(n);
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < np; ++k) W_symbolic(i, k) = value[W[i * np + k]];
      tau_symbolic[i] = value[tau[i]];
    }
    const Eigen::MatrixXd W_reference = reference.standard_regressor(q, dq, ddq);
    const double scale = std::max(1.0, W_reference.lpNorm<Eigen::Infinity>());
    EXPECT_LT((W_symbolic - W_reference).lpNorm<Eigen::Infinity>() / scale, 1e-12);
    EXPECT_LT(test::relative_error(tau_symbolic, reference.inverse_dynamics(q, dq, ddq, p)), 1e-12);
  }
}

class SymbolicNewtonEuler : public testing::TestWithParam<std::string> {};

TEST_P(SymbolicNewtonEuler, MatchesNumericReference) { expect_matches_reference(load_robot(GetParam())); }

TEST(SymbolicNewtonEulerTree, MatchesNumericReferenceThroughAPrismaticJointAndABranch) {
  // A prismatic body with children (its U and its origin, which moves with q, feed theirs),
  // a second branch and a fixed frame: shapes no shipped robot has.
  expect_matches_reference(load_mdh_yaml(
      "mixed.yaml",
      "name: mixed\n"
      "joints:\n"
      "  - {type: revolute, alpha: 0, d: 0, theta: 0, r: 0.3}\n"
      "  - {type: prismatic, alpha: -pi/2, d: 0.1, theta: pi/2, r: 0.2}\n"
      "  - {type: revolute, alpha: pi/2, d: 0.05, theta: 0, r: 0.4}\n"
      "  - {type: revolute, ant: 1, alpha: pi/3, d: 0.2, theta: 0.3, r: -0.1}\n"
      "  - {type: fixed, alpha: pi/4, d: 0.07, theta: 0.2, r: 0.15}\n"
      "  - {type: revolute, alpha: -pi/2, d: 0.12, theta: 0, r: 0.02}\n"));
}

INSTANTIATE_TEST_SUITE_P(All, SymbolicNewtonEuler, testing::ValuesIn(test::shipped_robots()),
                         test::robot_test_name);

}  // namespace
}  // namespace modelgen::gen
