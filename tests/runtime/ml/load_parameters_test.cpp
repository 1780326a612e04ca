// Load parameters (Swevers 2002 eq. 3) <-> standard parameters: against the generator's
// independent parallel-axis conversion (modelgen::standard_from_inertial), round trips, the 10 x 10
// Jacobian against Ceres automatic differentiation and central differences, and the
// physical-consistency warnings on hand-made loads.

#include "modelgen/ml/load_parameters.hpp"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "modelgen/model/robot_model.hpp"
#include "tests/support/kr150_load_scenario.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

LoadParameters random_load(test::Random& random) {
  LoadParameters load;
  load.mass = random.uniform(1, 200);
  for (double& c : load.com) c = random.uniform(-0.3, 0.3);
  for (int i = 0; i < 3; ++i) load.inertia[i] = random.uniform(5, 10);
  for (int i = 3; i < 6; ++i) load.inertia[i] = random.uniform(-1, 1);
  return load;
}

TEST(LoadParameters, StandardParametersMatchTheGeneratorsParallelAxisTheorem) {
  test::Random random(3);
  for (int trial = 0; trial < 50; ++trial) {
    const LoadParameters load = random_load(random);
    const auto& I = load.inertia;
    // modelgen::standard_from_inertial takes xx xy xz yy yz zz.
    const std::array<double, 10> expected = modelgen::standard_from_inertial(
        load.mass, load.com, {1, 0, 0, 0, 1, 0, 0, 0, 1}, {I[0], I[3], I[4], I[1], I[5], I[2]});
    const std::array<double, 10> actual = standard_from_load(load);
    for (int k = 0; k < 10; ++k) EXPECT_NEAR(actual[k], expected[k], 1e-12 * 200) << k;
  }
}

TEST(LoadParameters, RoundTrip) {
  test::Random random(4);
  for (int trial = 0; trial < 50; ++trial) {
    const LoadParameters load = random_load(random);
    const std::array<double, 10> standard = standard_from_load(load);
    const LoadParameters back = load_from_standard(standard.data());
    const auto a = load.to_vector(), b = back.to_vector();
    for (int k = 0; k < 10; ++k) EXPECT_NEAR(a[k], b[k], 1e-11 * std::max(1.0, std::abs(a[k])));
  }
}

TEST(LoadParameters, JacobianMatchesAutodiffAndCentralDifferences) {
  test::Random random(5);
  for (int trial = 0; trial < 20; ++trial) {
    const LoadParameters load = random_load(random);
    const Eigen::MatrixXd J = standard_from_load_jacobian(load);
    const auto v = load.to_vector();
    using Jet = ceres::Jet<double, 10>;
    Jet x[10], y[10];
    for (int l = 0; l < 10; ++l) x[l] = Jet(v[l], l);
    standard_from_load(x, y);
    for (int k = 0; k < 10; ++k) {
      for (int l = 0; l < 10; ++l) EXPECT_NEAR(J(k, l), y[k].v[l], 1e-12 * 400) << k << "," << l;
    }
    for (int l = 0; l < 10; ++l) {
      const double h = 1e-6 * std::max(1.0, std::abs(v[l]));
      auto plus = v, minus = v;
      plus[l] += h;
      minus[l] -= h;
      const auto fp = standard_from_load(LoadParameters::from_vector(plus.data()));
      const auto fm = standard_from_load(LoadParameters::from_vector(minus.data()));
      for (int k = 0; k < 10; ++k) {
        const double fd = (fp[k] - fm[k]) / (2 * h);
        EXPECT_NEAR(J(k, l), fd, 1e-8 * std::max(1.0, std::abs(J(k, l)))) << k << "," << l;
      }
    }
  }
}

TEST(LoadParameters, Table2LoadIsConsistent) {
  EXPECT_TRUE(physical_consistency_warnings(test::table2_load()).empty());
}

TEST(LoadParameters, WarningsNameWhatIsWrong) {
  LoadParameters load = test::table2_load();
  load.mass = -3;
  auto warnings = physical_consistency_warnings(load);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("mass -3 kg is not positive"), std::string::npos) << warnings[0];

  load = test::table2_load();
  load.inertia = {1, 1, 1, 2, 0, 0};  // eigenvalues -1, 1, 3
  warnings = physical_consistency_warnings(load);
  ASSERT_GE(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("not positive definite"), std::string::npos) << warnings[0];

  load = test::table2_load();
  load.inertia = {1, 1, 3, 0, 0, 0};  // positive definite, 3 > 1 + 1
  warnings = physical_consistency_warnings(load);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("triangle inequality"), std::string::npos) << warnings[0];

  load = test::table2_load();
  load.com[1] = std::nan("");
  warnings = physical_consistency_warnings(load);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("load_cy"), std::string::npos) << warnings[0];
}

TEST(LoadParameters, NoCentreOfGravityWithoutMass) {
  std::array<double, 10> standard = standard_from_load(test::table2_load());
  standard[9] = 0;
  try {
    load_from_standard(standard.data());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("mass M is 0 kg"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace modelgen
