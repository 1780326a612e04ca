// The checked-in generated code of one shipped robot (compiled from generated/, what ships)
// against independent computations on 10 000 seeded random states: the numeric reference's
// regressor and inverse dynamics, Orocos KDL on serial robots, and W p == tau within the
// generated code itself. Built once per robot with MODELGEN_ROBOT_* definitions.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include MODELGEN_ROBOT_HEADER
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace model = ::modelgen::MODELGEN_ROBOT_NAMESPACE;

// Random states per comparison; fewer in the sanitizer build (tests/CMakeLists.txt).
#ifdef MODELGEN_TEST_STATES
constexpr int kStates = MODELGEN_TEST_STATES;
#else
constexpr int kStates = 10000;
#endif

class GeneratedModel : public testing::Test {
 protected:
  GeneratedModel()
      : description_(modelgen::load_robot(test::source_path(MODELGEN_ROBOT_DESCRIPTION))),
        reference_(description_.tree) {}

  modelgen::RobotModel description_;
  ReferenceDynamics reference_;
};

TEST_F(GeneratedModel, ShapeAndNamesMatchTheDescription) {
  ASSERT_EQ(model::kDof, reference_.dof());
  ASSERT_EQ(model::kStandardParams, reference_.num_params());
  for (int k = 0; k < model::kStandardParams; ++k) {
    EXPECT_EQ(model::kStandardParamNames[k], description_.tree.params[k].name);
  }
}

TEST_F(GeneratedModel, EqualsNumericReferenceOnRandomStates) {
  const int n = model::kDof, np = model::kStandardParams;
  test::Random random(2024);
  std::vector<double> W(n * np), tau(n), tau_from_W(n);
  double worst_W = 0, worst_tau = 0;
  for (int s = 0; s < kStates; ++s) {
    const Eigen::VectorXd q = random.vector(n, -3.2, 3.2), dq = random.vector(n, -3, 3),
                          ddq = random.vector(n, -10, 10);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    model::idim_regressor_standard(q.data(), dq.data(), ddq.data(), W.data());
    model::inverse_dynamics_standard(q.data(), dq.data(), ddq.data(), p.data(), tau.data());
    const Eigen::MatrixXd W_reference = reference_.standard_regressor(q, dq, ddq);
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
        W_generated(W.data(), n, np);
    const double scale = std::max(1.0, W_reference.lpNorm<Eigen::Infinity>());
    worst_W = std::max(worst_W, (W_generated - W_reference).lpNorm<Eigen::Infinity>() / scale);
    const Eigen::VectorXd tau_reference = reference_.inverse_dynamics(q, dq, ddq, p);
    const Eigen::Map<const Eigen::VectorXd> tau_generated(tau.data(), n);
    worst_tau = std::max(worst_tau, test::relative_error(tau_generated, tau_reference, 1.0));
    // The two generated functions agree with each other: W p == tau.
    const Eigen::VectorXd Wp = W_generated * p;
    EXPECT_LT(test::relative_error(Wp, tau_generated, 1.0), 1e-10);
  }
  std::cout << "[ GENERATED] " << MODELGEN_ROBOT_DESCRIPTION << ": worst relative difference "
            << "regressor " << worst_W << ", inverse dynamics " << worst_tau << " over " << kStates
            << " states\n";
  // Issue 16: every generated function within 1e-12 of the reference (measured up to 5e-15).
  EXPECT_LT(worst_W, 1e-12);
  EXPECT_LT(worst_tau, 1e-12);
}

TEST_F(GeneratedModel, BaseParameterFunctionsEqualTheStandardModel) {
  const int n = model::kDof, np = model::kStandardParams, nb = model::kBaseParams;
  ASSERT_LE(nb, np);
  test::Random random(31);
  std::vector<double> beta(nb), W_base(n * nb), tau(n);
  double worst = 0;
  for (int s = 0; s < kStates; ++s) {
    const Eigen::VectorXd q = random.vector(n, -3.2, 3.2), dq = random.vector(n, -3, 3),
                          ddq = random.vector(n, -10, 10);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    model::base_from_standard(p.data(), beta.data());
    model::inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau.data());
    model::idim_regressor(q.data(), dq.data(), ddq.data(), W_base.data());
    // The base model reproduces the reference torques of the standard parameters.
    const Eigen::VectorXd expected = reference_.inverse_dynamics(q, dq, ddq, p);
    const Eigen::Map<const Eigen::VectorXd> tau_base(tau.data(), n);
    worst = std::max(worst, test::relative_error(tau_base, expected, 1.0));
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
        W(W_base.data(), n, nb);
    const Eigen::VectorXd W_beta = W * Eigen::Map<const Eigen::VectorXd>(beta.data(), nb);
    EXPECT_LT(test::relative_error(W_beta, expected, 1.0), 1e-10);
  }
  std::cout << "[ GENERATED] " << MODELGEN_ROBOT_DESCRIPTION << ": " << nb << " base parameters, "
            << "worst relative difference of the base inverse dynamics " << worst << "\n";
  EXPECT_LT(worst, 1e-12);
}

TEST_F(GeneratedModel, PowerModelSharesTheBaseParameters) {
  const int n = model::kDof, nb = model::kBaseParams;
  test::Random random(12);
  std::vector<double> beta(nb), h1(nb), h2(nb), dh(nb), s(n), c(n), dh_sc(nb);
  for (int state = 0; state < kStates; ++state) {
    const Eigen::VectorXd q = random.vector(n, -3.2, 3.2), dq = random.vector(n, -3, 3),
                          ddq = random.vector(n, -10, 10);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    model::base_from_standard(p.data(), beta.data());
    const Eigen::Map<const Eigen::VectorXd> b(beta.data(), nb);
    // Gautier & Briot eq. 9: dh . beta = dq . tau, with the reference torques.
    model::power_regressor(q.data(), dq.data(), ddq.data(), dh.data());
    const double power = Eigen::Map<const Eigen::VectorXd>(dh.data(), nb).dot(b);
    const double expected = dq.dot(reference_.inverse_dynamics(q, dq, ddq, p));
    EXPECT_NEAR(power, expected, 1e-10 * std::max(1.0, std::abs(expected)));
    // Energy differences between two states equal the reference's (H is defined up to a
    // constant once parameters are regrouped).
    const Eigen::VectorXd q2 = random.vector(n, -3.2, 3.2), dq2 = random.vector(n, -3, 3);
    model::energy_regressor(q.data(), dq.data(), h1.data());
    model::energy_regressor(q2.data(), dq2.data(), h2.data());
    const double difference = (Eigen::Map<const Eigen::VectorXd>(h1.data(), nb) -
                               Eigen::Map<const Eigen::VectorXd>(h2.data(), nb)).dot(b);
    const double expected_difference =
        reference_.kinetic_energy(q, dq, p) + reference_.potential_energy(q, p) -
        reference_.kinetic_energy(q2, dq2, p) - reference_.potential_energy(q2, p);
    EXPECT_NEAR(difference, expected_difference, 1e-10 * std::max(1.0, std::abs(expected_difference)));
    model::joint_sincos(q.data(), s.data(), c.data());
    model::power_regressor_sincos(q.data(), s.data(), c.data(), dq.data(), ddq.data(), dh_sc.data());
    EXPECT_EQ(dh, dh_sc);
  }
}

TEST_F(GeneratedModel, SincosVariantsEqualThePlainFunctions) {
  const int n = model::kDof, np = model::kStandardParams, nb = model::kBaseParams;
  test::Random random(5);
  std::vector<double> s(n), c(n), beta(nb);
  std::vector<double> W1(n * np), W2(n * np), Wb1(n * nb), Wb2(n * nb);
  std::vector<double> t1(n), t2(n), tb1(n), tb2(n);
  for (int state = 0; state < 1000; ++state) {
    const Eigen::VectorXd q = random.vector(n, -3.2, 3.2), dq = random.vector(n, -3, 3),
                          ddq = random.vector(n, -10, 10);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    model::joint_sincos(q.data(), s.data(), c.data());
    for (int i = 0; i < n; ++i) {
      EXPECT_EQ(s[i], std::sin(q[i]));
      EXPECT_EQ(c[i], std::cos(q[i]));
    }
    model::base_from_standard(p.data(), beta.data());
    model::idim_regressor_standard(q.data(), dq.data(), ddq.data(), W1.data());
    model::idim_regressor_standard_sincos(q.data(), s.data(), c.data(), dq.data(), ddq.data(), W2.data());
    model::inverse_dynamics_standard(q.data(), dq.data(), ddq.data(), p.data(), t1.data());
    model::inverse_dynamics_standard_sincos(q.data(), s.data(), c.data(), dq.data(), ddq.data(),
                                            p.data(), t2.data());
    model::idim_regressor(q.data(), dq.data(), ddq.data(), Wb1.data());
    model::idim_regressor_sincos(q.data(), s.data(), c.data(), dq.data(), ddq.data(), Wb2.data());
    model::inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tb1.data());
    model::inverse_dynamics_sincos(q.data(), s.data(), c.data(), dq.data(), ddq.data(), beta.data(),
                                   tb2.data());
    // Same statements on the same values: the same doubles.
    EXPECT_EQ(W1, W2);
    EXPECT_EQ(t1, t2);
    EXPECT_EQ(Wb1, Wb2);
    EXPECT_EQ(tb1, tb2);
  }
}

TEST_F(GeneratedModel, EqualsKdlOnSerialRobots) {
  if (!test::is_serial(description_.tree)) GTEST_SKIP() << "a tree: KDL's chain solver does not apply";
  const int n = model::kDof;
  test::Random random(99);
  std::vector<double> tau(n);
  double worst = 0;
  for (int s = 0; s < kStates; ++s) {
    const Eigen::VectorXd q = random.vector(n, -3.2, 3.2), dq = random.vector(n, -3, 3),
                          ddq = random.vector(n, -10, 10);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    model::inverse_dynamics_standard(q.data(), dq.data(), ddq.data(), p.data(), tau.data());
    const Eigen::VectorXd kdl = test::kdl_inverse_dynamics(description_.tree, q, dq, ddq, p);
    worst = std::max(worst, test::relative_error(Eigen::Map<const Eigen::VectorXd>(tau.data(), n), kdl, 1.0));
  }
  std::cout << "[ GENERATED] " << MODELGEN_ROBOT_DESCRIPTION << ": worst relative difference to KDL "
            << worst << " over " << kStates << " states\n";
  EXPECT_LT(worst, 1e-10);
}

TEST_F(GeneratedModel, FloatVariantAgreesToSinglePrecision) {
  const int n = model::kDof, np = model::kStandardParams;
  test::Random random(7);
  std::vector<float> qf(n), dqf(n), ddqf(n), pf(np), tauf(n), Wf(n * np);
  for (int s = 0; s < 1000; ++s) {
    const Eigen::VectorXd q = random.vector(n, -3.2, 3.2), dq = random.vector(n, -3, 3),
                          ddq = random.vector(n, -10, 10);
    const Eigen::VectorXd p = test::random_physical_parameters(description_.tree, random);
    // Feed the float functions the double values rounded to float, and compare with the
    // reference at those same rounded inputs, so only the arithmetic differs.
    Eigen::VectorXd qr(n), dqr(n), ddqr(n), pr(np);
    for (int i = 0; i < n; ++i) {
      qf[i] = static_cast<float>(q[i]), dqf[i] = static_cast<float>(dq[i]),
      ddqf[i] = static_cast<float>(ddq[i]);
      qr[i] = qf[i], dqr[i] = dqf[i], ddqr[i] = ddqf[i];
    }
    for (int k = 0; k < np; ++k) pf[k] = static_cast<float>(p[k]), pr[k] = pf[k];
    model::inverse_dynamics_standard(qf.data(), dqf.data(), ddqf.data(), pf.data(), tauf.data());
    model::idim_regressor_standard(qf.data(), dqf.data(), ddqf.data(), Wf.data());
    const Eigen::VectorXd expected = reference_.inverse_dynamics(qr, dqr, ddqr, pr);
    const Eigen::VectorXd got = Eigen::Map<const Eigen::VectorXf>(tauf.data(), n).cast<double>();
    EXPECT_LT(test::relative_error(got, expected, 1.0), 1e-4);
    const Eigen::MatrixXd W_reference = reference_.standard_regressor(qr, dqr, ddqr);
    const Eigen::MatrixXd W_float =
        Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            Wf.data(), n, np)
            .cast<double>();
    const double scale = std::max(1.0, W_reference.lpNorm<Eigen::Infinity>());
    EXPECT_LT((W_float - W_reference).lpNorm<Eigen::Infinity>() / scale, 1e-4);
  }
}

}  // namespace
}  // namespace modelgen
