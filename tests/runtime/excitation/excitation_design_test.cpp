// The gradient SLSQP is given (design_gradient.cpp: analytic through the Fourier series and
// the eigen-decomposition, the regressor's state derivative by differences for this numeric
// reference) against central differences of the objective itself, for both criteria, on the
// two-axis robot; design_gradient_test.cpp does the same on generated models.

#include "modelgen/excitation/excitation_design.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "modelgen/model/load_robot.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

class DesignGradient : public ::testing::TestWithParam<DesignCriterion> {};

TEST_P(DesignGradient, EqualsCentralDifferencesOfTheObjective) {
  const RobotModel robot = load_robot(test::source_path("tests/bad_inputs/robots/two_axes_limited.yaml"));
  const ReferenceModel model(robot.name, robot.tree, "", robot.drives);
  ExcitationDesignProblem problem;
  problem.model = &model;
  problem.period = 3;
  problem.harmonics = 2;
  problem.moving = {0, 1};
  problem.hold = Eigen::VectorXd::Zero(2);
  for (const JointDescription& joint : robot.joints) problem.limits.push_back(joint.limits);
  problem.criterion = GetParam();
  problem.samples = 40;
  std::vector<int> columns;
  for (int c = 0; c < model.num_base_params(); ++c) columns.push_back(c);
  // Any positive fixed scale; uneven on purpose.
  Eigen::VectorXd scale(model.num_base_params());
  for (Eigen::Index c = 0; c < scale.size(); ++c) scale[c] = 0.5 + 0.1 * static_cast<double>(c);
  std::mt19937 engine(3);
  std::uniform_real_distribution<double> uniform(-0.4, 0.4);
  std::vector<double> x(10);
  for (double& v : x) v = uniform(engine);

  std::vector<double> gradient;
  const double value = design_objective(problem, columns, scale, x, &gradient);
  ASSERT_TRUE(std::isfinite(value));
  ASSERT_EQ(gradient.size(), x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double h = 1e-6;
    std::vector<double> up = x, down = x;
    up[i] += h, down[i] -= h;
    const double numeric = (design_objective(problem, columns, scale, up, nullptr) -
                            design_objective(problem, columns, scale, down, nullptr)) / (2 * h);
    EXPECT_NEAR(gradient[i], numeric, 1e-4 * std::max(1.0, std::abs(numeric))) << "variable " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Criteria, DesignGradient,
                         ::testing::Values(DesignCriterion::kCond, DesignCriterion::kLogDet),
                         [](const auto& info) {
                           return info.param == DesignCriterion::kCond ? "cond" : "logdet";
                         });

TEST(DesignConstraints, JacobianEqualsCentralDifferencesWithEffortLimits) {
  // The a-priori values are random standard parameters (link 2's centre of mass off axis 2,
  // so the torques depend on q and dq too, and on friction where the description has it);
  // two_axes_limited.yaml has no effort limits and gets 2.5 N m on both joints.
  for (const char* description : {"tests/bad_inputs/robots/two_axes_effort.yaml",
                                  "tests/bad_inputs/robots/two_axes_limited.yaml"}) {
    const RobotModel robot = load_robot(test::source_path(description));
    const ReferenceModel model(robot.name, robot.tree, "", robot.drives);
    ExcitationDesignProblem problem;
    problem.model = &model;
    problem.period = 3;
    problem.harmonics = 2;
    problem.moving = {0, 1};
    problem.hold = Eigen::VectorXd::Zero(2);
    for (const JointDescription& joint : robot.joints) problem.limits.push_back(joint.limits);
    for (JointLimits& limits : problem.limits) limits.effort = limits.effort.value_or(2.5);
    // A-priori values with every term present: random standard parameters.
    test::Random random(8);
    const Eigen::VectorXd standard = random.vector(model.num_standard_params(), 0.1, 1.0);
    problem.a_priori.resize(model.num_base_params());
    model.base_from_standard(standard.data(), problem.a_priori.data());
    std::mt19937 engine(4);
    std::uniform_real_distribution<double> uniform(-0.4, 0.4);
    std::vector<double> x(10);
    for (double& v : x) v = uniform(engine);

    std::vector<double> jacobian;
    const std::vector<double> c = design_constraints(problem, x, &jacobian);
    const std::size_t kinematic = 2 * 16 * 2 * 6, effort = 2 * 16 * 2 * 2;
    ASSERT_EQ(c.size(), kinematic + effort) << description;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double h = 1e-6;
      std::vector<double> up = x, down = x;
      up[i] += h, down[i] -= h;
      const std::vector<double> c_up = design_constraints(problem, up, nullptr);
      const std::vector<double> c_down = design_constraints(problem, down, nullptr);
      for (std::size_t r = 0; r < c.size(); ++r) {
        const double numeric = (c_up[r] - c_down[r]) / (2 * h);
        ASSERT_NEAR(jacobian[r * x.size() + i], numeric, 1e-5 * std::max(1.0, std::abs(numeric)))
            << description << ": constraint " << r << ", variable " << i;
      }
    }
  }
}

}  // namespace
}  // namespace modelgen
