// The design's derivatives on shipped 6-axis robots (issue 28): the criterion's gradient SLSQP
// is given (design_gradient.cpp: through the generated state Jacobian for a generated model, by
// differences of the regressor for the numeric reference) and the Jacobian of the effort
// constraints (one state Jacobian at the a-priori values per point), both against central
// differences of the whole objective and constraints taken here. The TX-40 (coupled wrist
// joints 5-6) and the KR150 (coupled wrist 4-6) as generated models, and the TX-40's numeric
// reference; cond takes the criterion's 2 factors, logdet the rows of d value / d W.

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "modelgen/excitation/excitation_design.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "runtime/cli/common/shipped_models.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

struct Case {
  std::string label;
  const char* shipped;      // compiled-in generated model, or nullptr: the numeric reference
  const char* description;  // the description it was generated from
};

struct Scenario {
  RobotModel description;
  std::unique_ptr<IdentificationModel> model;
  ExcitationDesignProblem problem;
  std::vector<double> x;  // per joint q0, a_1..a_L, b_1..b_L
};

constexpr int kHarmonics = 3;

// All six axes moving, 3 harmonics, 120 samples; limits (which the constraints need) filled in
// where the description has none; random variables with amplitudes falling as 1/l.
Scenario make_scenario(const Case& c, std::uint64_t seed) {
  Scenario s;
  s.description = load_robot(test::source_path(c.description));
  if (c.shipped != nullptr) {
    s.model = internal::make_shipped_model(c.shipped);
  } else {
    s.model = std::make_unique<ReferenceModel>(s.description.name, s.description.tree, "",
                                               s.description.drives);
  }
  const int n = s.model->dof();
  ExcitationDesignProblem& p = s.problem;
  p.model = s.model.get();
  p.period = 10;
  p.harmonics = kHarmonics;
  p.samples = 120;
  p.hold = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < n; ++j) {
    p.moving.push_back(j);
    JointLimits limits = s.description.joints[static_cast<std::size_t>(j)].limits;
    limits.q_lower = limits.q_lower.value_or(-3), limits.q_upper = limits.q_upper.value_or(3);
    limits.dq = limits.dq.value_or(2), limits.ddq = limits.ddq.value_or(10);
    p.limits.push_back(limits);
  }
  test::Random random(seed);
  for (int j = 0; j < n; ++j) {
    s.x.push_back(random.uniform(-0.5, 0.5));
    for (int ab = 0; ab < 2; ++ab) {
      for (int l = 1; l <= kHarmonics; ++l) s.x.push_back(random.uniform(-0.3, 0.3) / l);
    }
  }
  return s;
}

// The column scale of design_criterion.hpp computed here: the norms of the columns of the
// regressor stacked over the trajectory of x.
Eigen::VectorXd column_norms(const Scenario& s) {
  const int n = s.model->dof(), per_axis = 2 * kHarmonics + 1;
  Eigen::VectorXd q0(n);
  Eigen::MatrixXd a(n, kHarmonics), b(n, kHarmonics);
  for (int j = 0; j < n; ++j) {
    const double* v = s.x.data() + j * per_axis;
    q0[j] = v[0];
    for (int l = 0; l < kHarmonics; ++l) a(j, l) = v[1 + l], b(j, l) = v[1 + kHarmonics + l];
  }
  const Eigen::MatrixXd W =
      stacked_regressor(*s.model, to_trajectory(q0, a, b, s.problem.period), s.problem.samples);
  return W.colwise().norm().transpose();
}

const Case kCases[] = {{"tx40", "tx40", "robots/tx40.yaml"},
                       {"kr150", "kr150", "robots/kr150.yaml"},
                       {"tx40_reference", nullptr, "robots/tx40.yaml"}};

TEST(DesignGradientOnShippedRobots, EqualsCentralDifferencesOfTheObjective) {
  for (const Case& c : kCases) {
    for (const DesignCriterion criterion : {DesignCriterion::kCond, DesignCriterion::kLogDet}) {
      const std::string name =
          c.label + (criterion == DesignCriterion::kCond ? " cond" : " logdet");
      Scenario s = make_scenario(c, 21);
      ASSERT_NE(s.model, nullptr) << name;
      // Both routes of design_gradient.cpp are covered: generated models differentiate
      // through their state Jacobian, the reference by differences of its regressor.
      EXPECT_EQ(s.model->exact_state_jacobian(), c.shipped != nullptr) << name;
      s.problem.criterion = criterion;
      std::vector<int> columns(static_cast<std::size_t>(s.model->num_base_params()));
      for (std::size_t i = 0; i < columns.size(); ++i) columns[i] = static_cast<int>(i);
      const Eigen::VectorXd scale = column_norms(s);

      std::vector<double> gradient;
      const double value = design_objective(s.problem, columns, scale, s.x, &gradient);
      ASSERT_TRUE(std::isfinite(value)) << name;
      ASSERT_EQ(gradient.size(), s.x.size()) << name;
      Eigen::VectorXd numeric(static_cast<Eigen::Index>(s.x.size()));
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        const double h = 1e-5;
        std::vector<double> up = s.x, down = s.x;
        up[i] += h, down[i] -= h;
        numeric[static_cast<Eigen::Index>(i)] =
            (design_objective(s.problem, columns, scale, up, nullptr) -
             design_objective(s.problem, columns, scale, down, nullptr)) /
            (2 * h);
      }
      // The differences' own error limits this: lambda_min of (W D)^T (W D) carries round-off
      // near eps cond(W D)^2 of itself (about 1e-10 in the value for the KR150), so h = 1e-5
      // gives errors up to 2e-6 of the largest entry, and halving or doubling h moves them. A
      // wrong term of the gradient (a factor, a column, a route) is of order 1.
      const double tolerance = 1e-5 * numeric.cwiseAbs().maxCoeff();
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        EXPECT_NEAR(gradient[i], numeric[static_cast<Eigen::Index>(i)], tolerance)
            << name << ": variable " << i;
      }
    }
  }
}

TEST(DesignGradientOnShippedRobots, EffortConstraintJacobianEqualsCentralDifferences) {
  for (const Case& c : kCases) {
    Scenario s = make_scenario(c, 22);
    // A-priori values with every term present: random physical standard parameters (drive
    // inertias and friction included), through the reference's regrouping.
    test::Random random(9);
    const Eigen::VectorXd standard = test::random_physical_parameters(s.description.tree, random);
    const ReferenceModel reference(s.description.name, s.description.tree);
    s.problem.a_priori.resize(s.model->num_base_params());
    reference.base_from_standard(standard.data(), s.problem.a_priori.data());
    for (JointLimits& limits : s.problem.limits) limits.effort = limits.effort.value_or(500);

    std::vector<double> jacobian;
    const std::vector<double> constraints = design_constraints(s.problem, s.x, &jacobian);
    const std::size_t n = s.x.size(), points = 16 * kHarmonics;
    const std::size_t kinematic = 6 * points * 6, effort = 6 * points * 2;
    ASSERT_EQ(constraints.size(), kinematic + effort) << c.label;
    // Central differences of every effort constraint in every variable, taken here.
    Eigen::MatrixXd numeric(static_cast<Eigen::Index>(effort), static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
      const double h = 1e-6;
      std::vector<double> up = s.x, down = s.x;
      up[i] += h, down[i] -= h;
      const std::vector<double> c_up = design_constraints(s.problem, up, nullptr);
      const std::vector<double> c_down = design_constraints(s.problem, down, nullptr);
      for (std::size_t r = 0; r < effort; ++r) {
        numeric(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(i)) =
            (c_up[kinematic + r] - c_down[kinematic + r]) / (2 * h);
      }
    }
    // h = 1e-6 on torques over their limits of order 1: round-off near 1e-10.
    const double tolerance = 1e-6 * std::max(1.0, numeric.cwiseAbs().maxCoeff());
    double worst = 0;
    for (std::size_t r = 0; r < effort; ++r) {
      for (std::size_t i = 0; i < n; ++i) {
        worst = std::max(
            worst, std::abs(jacobian[(kinematic + r) * n + i] -
                            numeric(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(i))));
      }
    }
    EXPECT_LT(worst, tolerance) << c.label << ": largest entry " << numeric.cwiseAbs().maxCoeff();
    EXPECT_GT(numeric.cwiseAbs().maxCoeff(), 1e-3) << c.label << ": torques depend on x";
  }
}

}  // namespace
}  // namespace modelgen
