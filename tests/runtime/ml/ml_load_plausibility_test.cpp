// What the maximum-likelihood fit decided of the load and the drives, and whether the load is
// plausible (modelgen/ml/load_plausibility.hpp), on the simulated KR150 load experiment of
// Swevers et al. 2002 (tests/support/kr150_load_scenario.hpp). Oracles: the truth the data are
// simulated from, the section 4.2 result that a wrist-only experiment leaves the load mass
// free, the unconstrained fit's standard deviation of a parameter the consistent fit holds on
// its bound, the marginal covariance computed here from the Jacobian, and closed forms (the
// KR150's segment lengths from its YAML, a point mass's extent in a sphere).

#include "modelgen/ml/load_plausibility.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "modelgen/ml/fit.hpp"
#include "modelgen/ml/physical_fit.hpp"
#include "tests/support/kr150_load_scenario.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using Scenario = test::Kr150LoadScenario;

Eigen::Index index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto found = std::find(names.begin(), names.end(), name);
  EXPECT_NE(found, names.end()) << name;
  return found - names.begin();
}

// New noisy motor torques of the scenario's trajectory for `truth`, noise seeded by `seed`.
MlExperiment simulate(Scenario& scenario, const Eigen::VectorXd& truth, unsigned seed) {
  MlExperiment data = scenario.data;
  MlSetup setup;
  setup.unknown = {"Rv4"};
  setup.payload_link = 7;
  MlProblem problem(*scenario.model, {data}, setup, truth);
  const Eigen::VectorXd theta = problem.drive_parameters(truth);
  scenario.model->set_samples(data.q, data.dq, data.ddq);
  test::Random random(seed);
  for (Eigen::Index s = 0; s < data.q.rows(); ++s) {
    double tau[6];
    scenario.model->torque(static_cast<int>(s), theta.data(), tau);
    for (int i = 0; i < 6; ++i) data.tau_M(s, i) = tau[i] + data.sigma[i] * random.normal();
  }
  return data;
}

TEST(MlLoadPlausibility, TheArmReachIsTheSumOfTheKr150Segments) {
  Scenario scenario(true, 100);
  const RobotModel& robot = scenario.description;
  // robots/kr150.yaml: d2 = 0.35, d3 = 1.25, (d4, r4) = (0.055, -1.1), flange r = -0.23.
  const double expected = 0.35 + 1.25 + std::hypot(0.055, 1.1) + 0.23;
  EXPECT_NEAR(arm_reach(robot.tree, robot.payload_body), expected, 1e-12);
}

// A hand-made fit of a load alone, every unknown identifiable.
MlFitResult load_fit(const LoadParameters& load) {
  MlFitResult fit;
  fit.names = load_param_names();
  fit.identifiability.identifiable.assign(fit.names.size(), true);
  fit.has_load = true;
  fit.load = load;
  const auto v = load.to_vector();
  fit.value = Eigen::Map<const Eigen::VectorXd>(v.data(), kLoadParams);
  fit.std_dev = Eigen::VectorXd::Zero(kLoadParams);
  return fit;
}

TEST(MlLoadPlausibility, ALoadBeyondTheReachOrOutsideItsRegionIsWarnedAbout) {
  LoadParameters point;
  point.mass = 10;
  point.com = {0.2, 0, 0};
  BodyRegion sphere;
  sphere.semi_axes = {0.1, 0.1, 0.1};
  // A point mass at twice the sphere's radius: extent exactly 2.
  MlLoadSummary outside = summarise_ml_load(load_fit(point), false, 3.0, sphere, 7);
  ASSERT_TRUE(outside.region_extent.has_value());
  EXPECT_NEAR(*outside.region_extent, 2.0, 1e-12);
  ASSERT_EQ(outside.warnings.size(), 1u);
  EXPECT_NE(outside.warnings[0].find("outside"), std::string::npos) << outside.warnings[0];
  point.com = {0.05, 0, 0};
  EXPECT_TRUE(summarise_ml_load(load_fit(point), false, 3.0, sphere, 7).warnings.empty());
  point.com = {3, 4, 0};  // 5 m from the flange, reach 3 m
  const MlLoadSummary far = summarise_ml_load(load_fit(point), false, 3.0, std::nullopt, 7);
  EXPECT_NEAR(far.com_distance, 5.0, 1e-12);
  ASSERT_EQ(far.warnings.size(), 1u);
  EXPECT_NE(far.warnings[0].find("reach"), std::string::npos) << far.warnings[0];
}

TEST(MlLoadPlausibility, TheDataDecideTheLoadOfAFullExperimentWithinItsSpread) {
  Scenario scenario(true, 400);
  MlSetup setup;
  setup.unknown = scenario.unknowns({2, 3, 4, 5});
  setup.payload_link = 7;
  MlProblem problem(*scenario.model, {scenario.data}, setup, scenario.start(setup.unknown));
  const MlFitResult fit = fit_ml(problem);
  const MlLoadSummary load = summarise_ml_load(fit, false, 3.0, std::nullopt, 7);
  EXPECT_EQ(load.mass_by, MlDecidedBy::kData);
  EXPECT_EQ(load.com_by, MlDecidedBy::kData);
  EXPECT_EQ(load.moments_by, MlDecidedBy::kData);
  EXPECT_TRUE(load.warnings.empty());
  const LoadParameters truth = test::table2_load();
  EXPECT_NEAR(load.mass, truth.mass, 4 * fit.load_std_dev.mass);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(load.com[i], truth.com[i], 4 * fit.load_std_dev.com[i]) << "c" << i;
  }
  for (const MlDriveSummary& drive : summarise_ml_drives(fit, {})) {
    EXPECT_EQ(drive.by, MlDecidedBy::kData) << drive.name;
    EXPECT_NEAR(drive.value, scenario.truth[index_of(scenario.names, drive.name)],
                4 * drive.std_dev)
        << drive.name;
  }
}

TEST(MlLoadPlausibility, AWristOnlyExperimentLeavesTheLoadUndetermined) {
  // Swevers section 4.2: moving only the wrist leaves the load mass free (rank 18 of 19), and
  // with it the centre of gravity and the inertia about it.
  Scenario scenario(false, 400);
  MlSetup setup;
  setup.unknown = scenario.unknowns({3, 4, 5});
  setup.payload_link = 7;
  MlProblem problem(*scenario.model, {scenario.data}, setup, scenario.start(setup.unknown));
  const MlFitResult fit = fit_ml(problem);
  ASSERT_LT(fit.identifiability.rank, static_cast<int>(fit.names.size()));
  const MlLoadSummary load = summarise_ml_load(fit, false, 3.0, std::nullopt, 7);
  EXPECT_EQ(load.mass_by, MlDecidedBy::kUndetermined);
  EXPECT_EQ(load.com_by, MlDecidedBy::kUndetermined);
  EXPECT_TRUE(std::isnan(load.mass));
  EXPECT_TRUE(std::isnan(load.com[0]));
  EXPECT_TRUE(load.warnings.empty());  // nothing reported, nothing judged
  // The consistent fit reports no number for them either, whatever its prior term chose.
  const MlPhysicalResult physical = fit_ml_physical(problem, fit);
  const MlLoadSummary consistent =
      summarise_ml_load(physical.fit, physical.load_on_boundary, 3.0, std::nullopt, 7);
  EXPECT_EQ(consistent.mass_by, MlDecidedBy::kUndetermined);
  EXPECT_TRUE(std::isnan(consistent.mass));
  for (const MlDriveSummary& drive : summarise_ml_drives(physical.fit, physical.at_bound)) {
    EXPECT_EQ(std::isnan(drive.value), drive.by == MlDecidedBy::kUndetermined) << drive.name;
  }
}

TEST(MlLoadPlausibility, AFrictionOnItsBoundHasTheUnconstrainedSpreadNotZero) {
  Scenario scenario(true, 400);
  Eigen::VectorXd truth = scenario.truth;
  truth[index_of(scenario.names, "Rv6")] = 0;  // a frictionless motor: on the bound
  MlSetup setup;
  setup.unknown = scenario.unknowns({2, 3, 4, 5});
  setup.payload_link = 7;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    const MlExperiment data = simulate(scenario, truth, seed);
    MlProblem problem(*scenario.model, {data}, setup, scenario.start(setup.unknown));
    const MlFitResult unconstrained = fit_ml(problem);
    const Eigen::Index rv6 = index_of(unconstrained.names, "Rv6");
    if (!(unconstrained.value[rv6] < 0)) continue;
    const MlPhysicalResult physical = fit_ml_physical(problem, unconstrained);
    ASSERT_EQ(physical.at_bound.size(), unconstrained.names.size());
    ASSERT_TRUE(physical.at_bound[static_cast<std::size_t>(rv6)]);
    const double sd = physical.fit.std_dev[rv6];
    // The marginal standard deviation with Rv6 free, computed here at the consistent optimum.
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    problem.evaluate(physical.fit.value, r, &J);
    const double s2 = r.squaredNorm() / static_cast<double>(J.rows() - J.cols());
    const Eigen::MatrixXd covariance = s2 * (J.transpose() * J).inverse();
    EXPECT_NEAR(sd, std::sqrt(covariance(rv6, rv6)), 1e-3 * sd);  // s^2: held counted or not
    // ... and the unconstrained fit's own, at its optimum: within 10 %.
    EXPECT_GT(sd, 0.9 * unconstrained.std_dev[rv6]);
    EXPECT_LT(sd, 1.1 * unconstrained.std_dev[rv6]);
    for (const MlDriveSummary& drive : summarise_ml_drives(physical.fit, physical.at_bound)) {
      EXPECT_EQ(drive.by, drive.name == "Rv6" ? MlDecidedBy::kBound : MlDecidedBy::kData)
          << drive.name;
    }
    return;
  }
  FAIL() << "no seed gave a negative Rv6";
}

}  // namespace
}  // namespace modelgen
