// The consistent maximum-likelihood fit (modelgen/ml/physical_fit.hpp) on the simulated KR150
// load experiment of Swevers et al. 2002 (tests/support/kr150_load_scenario.hpp), with truths
// on the boundary of the consistent set so that noise pushes the unconstrained fit outside it:
// a viscous friction of 0 and a point-mass load. Oracles: the unconstrained fit with the bound
// parameter known at its bound (the constrained optimum must be that fit), and random
// consistent perturbations of the optimum (none may lower the cost).

#include "modelgen/ml/physical_fit.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/ml/fit.hpp"
#include "modelgen/model/pseudo_inertia.hpp"
#include "tests/support/kr150_load_scenario.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using Scenario = test::Kr150LoadScenario;

Eigen::Index index_of(const Scenario& scenario, const std::string& name) {
  const auto found = std::find(scenario.names.begin(), scenario.names.end(), name);
  EXPECT_NE(found, scenario.names.end()) << name;
  return found - scenario.names.begin();
}

// New noisy motor torques of the scenario's trajectory for `truth` (every ml_param_names()
// value), through the reference drive model, noise seeded by `seed`.
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

double value_of(const MlFitResult& fit, const std::string& name) {
  const auto found = std::find(fit.names.begin(), fit.names.end(), name);
  EXPECT_NE(found, fit.names.end()) << name;
  return fit.value[found - fit.names.begin()];
}

// Half the weighted sum of squares of eq. 18 at the unknowns theta1.
double cost(const MlProblem& problem, const Eigen::VectorXd& theta1) {
  Eigen::VectorXd r;
  problem.evaluate(theta1, r, nullptr);
  return 0.5 * r.squaredNorm();
}

TEST(MlPhysicalFit, AConsistentEstimateIsKept) {
  Scenario scenario(true, 400);
  MlSetup setup;
  setup.unknown = scenario.unknowns({2, 3, 4, 5});
  setup.payload_link = 7;
  MlProblem problem(*scenario.model, {scenario.data}, setup, scenario.start(setup.unknown));
  const MlFitResult unconstrained = fit_ml(problem);
  const std::vector<std::string> violations = ml_physical_violations(problem, unconstrained);
  ASSERT_TRUE(violations.empty()) << violations.front();
  const MlPhysicalResult physical = fit_ml_physical(problem, unconstrained);
  EXPECT_TRUE(physical.unconstrained_consistent);
  EXPECT_TRUE(physical.binding.empty());
  EXPECT_EQ(physical.cost_increase, 0);
  EXPECT_EQ(physical.fit.value, unconstrained.value);
}

TEST(MlPhysicalFit, AFrictionBoundIsTheFitWithTheFrictionKnownAtZero) {
  Scenario scenario(true, 400);
  Eigen::VectorXd truth = scenario.truth;
  truth[index_of(scenario, "Rv6")] = 0;  // a frictionless motor: on the bound
  MlSetup setup;
  setup.unknown = scenario.unknowns({2, 3, 4, 5});
  setup.payload_link = 7;
  // The first noise seed for which the unconstrained estimate of Rv6 comes out negative.
  for (unsigned seed = 1; seed <= 12; ++seed) {
    const MlExperiment data = simulate(scenario, truth, seed);
    MlProblem problem(*scenario.model, {data}, setup, scenario.start(setup.unknown));
    const MlFitResult unconstrained = fit_ml(problem);
    if (!(value_of(unconstrained, "Rv6") < 0)) continue;
    const std::vector<std::string> violations = ml_physical_violations(problem, unconstrained);
    ASSERT_FALSE(violations.empty());
    EXPECT_EQ(violations[0].rfind("Rv6 = -", 0), 0u) << violations[0];

    const MlPhysicalResult physical = fit_ml_physical(problem, unconstrained);
    EXPECT_FALSE(physical.unconstrained_consistent);
    EXPECT_EQ(physical.binding, std::vector<std::string>{"Rv6 >= 0"});
    EXPECT_EQ(value_of(physical.fit, "Rv6"), 0.0);
    EXPECT_TRUE(ml_physical_violations(problem, physical.fit).empty());
    EXPECT_GE(physical.cost_increase, 0);
    EXPECT_NEAR(physical.cost_increase,
                2 * (cost(problem, physical.fit.value) - cost(problem, unconstrained.value)),
                1e-9 * unconstrained.final_cost);

    // Oracle: Rv6 known at 0, everything else unknown, fitted without constraints.
    MlSetup known = setup;
    known.unknown.erase(std::find(known.unknown.begin(), known.unknown.end(), "Rv6"));
    Eigen::VectorXd values = scenario.start(known.unknown);
    values[index_of(scenario, "Rv6")] = 0;
    MlProblem reference_problem(*scenario.model, {data}, known, values);
    const MlFitResult reference = fit_ml(reference_problem);
    std::printf("constrained cost %.10g (%d it, converged %d, %s), reference cost %.10g\n",
                cost(problem, physical.fit.value), physical.fit.iterations, physical.fit.converged,
                physical.fit.solver_report.c_str(), reference.final_cost);
    for (std::size_t u = 0; u < reference.names.size(); ++u) {
      const double expected = reference.value[static_cast<Eigen::Index>(u)];
      const double sd = reference.std_dev[static_cast<Eigen::Index>(u)];
      EXPECT_NEAR(value_of(physical.fit, reference.names[u]), expected, 1e-4 * sd)
          << reference.names[u];
    }
    std::printf("seed %u: Rv6 %.4g -> 0, cost increase %.4g (of %.6g)\n", seed,
                value_of(unconstrained, "Rv6"), physical.cost_increase,
                2 * unconstrained.final_cost);
    return;
  }
  FAIL() << "no seed gave a negative Rv6";
}

TEST(MlPhysicalFit, APointMassLoadStaysConsistent) {
  Scenario scenario(true, 400);
  Eigen::VectorXd truth = scenario.truth;
  // A point mass: no inertia about its centre of gravity, on the boundary of the cone.
  for (const char* name :
       {"load_Ixx", "load_Iyy", "load_Izz", "load_Ixy", "load_Ixz", "load_Iyz"}) {
    truth[index_of(scenario, name)] = 0;
  }
  MlSetup setup;
  setup.unknown = scenario.unknowns({2, 3, 4, 5});
  setup.payload_link = 7;
  for (unsigned seed = 1; seed <= 12; ++seed) {
    const MlExperiment data = simulate(scenario, truth, seed);
    MlProblem problem(*scenario.model, {data}, setup, scenario.start(setup.unknown));
    const MlFitResult unconstrained = fit_ml(problem);
    const std::vector<std::string> violations = ml_physical_violations(problem, unconstrained);
    bool load_violation = false;
    for (const std::string& v : violations) load_violation |= v.rfind("load: ", 0) == 0;
    if (!load_violation) continue;

    const MlPhysicalResult physical = fit_ml_physical(problem, unconstrained);
    EXPECT_TRUE(ml_physical_violations(problem, physical.fit).empty());
    EXPECT_TRUE(physical.fit.load_warnings.empty());
    EXPECT_NE(
        std::find(physical.binding.begin(), physical.binding.end(), "load pseudo-inertia > 0"),
        physical.binding.end());
    EXPECT_GE(physical.cost_increase, 0);
    // The prediction is hardly worse: rms torque errors within 5 % of the unconstrained.
    for (const int i : {2, 3, 4, 5}) {
      EXPECT_LT(physical.fit.rms_error[i], 1.05 * unconstrained.rms_error[i]) << "axis " << i + 1;
    }
    // Local optimality against consistent perturbations: random small changes of the load's
    // log-Cholesky parameters and of the drive unknowns (kept within their bounds).
    const Eigen::VectorXd optimum = physical.fit.value;
    const double best = cost(problem, optimum);
    const std::array<double, 10> standard_array = standard_from_load(physical.fit.load);
    const auto log_cholesky = log_cholesky_from_inertial(standard_array.data());
    ASSERT_TRUE(log_cholesky.has_value());
    test::Random random(seed);
    for (int trial = 0; trial < 200; ++trial) {
      Eigen::VectorXd theta1 = optimum;
      Eigen::Matrix<double, 10, 1> moved = *log_cholesky;
      for (int i = 0; i < 10; ++i) moved[i] += 1e-4 * random.normal();
      double standard[10];
      inertial_from_log_cholesky(moved.data(), standard);
      const LoadParameters perturbed = load_from_standard(standard);
      const std::array<double, 10> values = perturbed.to_vector();
      for (int i = 0; i < 10; ++i) theta1[i] = values[static_cast<std::size_t>(i)];
      for (Eigen::Index u = 10; u < theta1.size(); ++u) {
        theta1[u] = std::max(0.0, theta1[u] * (1 + 1e-5 * random.normal()));
        if (physical.fit.names[static_cast<std::size_t>(u)].rfind("Rz", 0) == 0) {
          theta1[u] = std::min(theta1[u], 1.0);
        }
      }
      // A perturbed cost below the optimum by more than the prior term allows is a failure.
      EXPECT_GE(cost(problem, theta1), best - 1e-6 * best) << "trial " << trial;
    }
    std::printf("seed %u: violations", seed);
    for (const std::string& v : violations) std::printf(" [%s]", v.c_str());
    std::printf("\n  cost increase %.4g of %.6g; binding:", physical.cost_increase,
                2 * unconstrained.final_cost);
    for (const std::string& b : physical.binding) std::printf(" [%s]", b.c_str());
    std::printf("\n  mass %.4g (truth %.4g)\n", physical.fit.load.mass,
                truth[index_of(scenario, "load_m")]);
    return;
  }
  FAIL() << "no seed gave an impossible load";
}

TEST(MlPhysicalFit, APartlyKnownLoadIsRefused) {
  Scenario scenario(true, 100);
  MlSetup setup;
  setup.unknown = {"load_cx", "load_cy", "load_cz", "Rv4"};
  setup.payload_link = 7;
  Eigen::VectorXd values = scenario.truth;
  values[index_of(scenario, "Rv4")] = -1;  // inconsistent, so the constrained search is needed
  MlProblem problem(*scenario.model, {scenario.data}, setup, values);
  MlFitResult fit;
  fit.names = problem.unknown_names();
  fit.all_values = values;
  fit.value = problem.initial();
  try {
    fit_ml_physical(problem, fit);
    FAIL() << "no error";
  } catch (const EstimationError& error) {
    EXPECT_NE(std::string(error.what()).find("all unknown or all known"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace modelgen
