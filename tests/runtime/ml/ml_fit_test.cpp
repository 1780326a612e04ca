// Maximum-likelihood load identification (Swevers 2002, eq. 18, sections 3.2 and 4) on a
// simulated KR150: the Table 1 excitation of axes 3-6 (period 36.96 s, 1540 samples), the Table 2
// load, transmission efficiencies below 1 and noise on the averaged motor torques. Checks the
// cost's analytic Jacobian against Ceres automatic differentiation through the templated
// reference model and against central differences, the rank analysis of section 4.2 (axes 3-6:
// 22 unknowns, full rank; wrist only: 19 unknowns, rank 18, load mass named), and that approach 3
// recovers the load within Table 2's approach-3 errors.

#include "modelgen/ml/fit.hpp"
#include "modelgen/ml/identifiability.hpp"
#include "modelgen/ml/linear_route.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/ml/problem.hpp"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/signal/prepare.hpp"
#include "tests/support/kr150_load_scenario.hpp"
#include "tests/support/ml_residuals_direct.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using Scenario = test::Kr150LoadScenario;
constexpr const double* kSigma = Scenario::kSigma;

TEST(MlProblem, JacobianMatchesAutodiffAndCentralDifferences) {
  Scenario scenario(true, 300);
  const std::vector<std::string> unknown = scenario.unknowns({2, 3, 4, 5});
  MlSetup setup;
  setup.unknown = unknown;
  setup.payload_link = 7;
  setup.samples_per_block = 37;
  // Evaluate away from the truth so that every term of the chain rule matters.
  Eigen::VectorXd values = scenario.truth;
  test::Random random(9);
  for (size_t k = 0; k < scenario.names.size(); ++k) {
    if (std::find(unknown.begin(), unknown.end(), scenario.names[k]) != unknown.end()) {
      values[static_cast<Eigen::Index>(k)] *= random.uniform(0.8, 1.2);
    }
  }
  MlProblem problem(*scenario.model, {scenario.data}, setup, values);
  ASSERT_EQ(problem.num_unknowns(), 22);
  ASSERT_EQ(problem.axes(), (std::vector<int>{2, 3, 4, 5}));
  ASSERT_EQ(problem.num_residuals(), 300 * 4);
  const Eigen::VectorXd theta1 = problem.initial();
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  problem.evaluate(theta1, r, &J);

  // Oracle: the same residuals written directly with Jets through the templated model and
  // standard_from_load; nothing of MlProblem's chain rule is used.
  constexpr int kU = 22;
  using Jet = ceres::Jet<double, kU>;
  std::vector<Jet> theta1_jet(kU), residuals(static_cast<size_t>(problem.num_residuals()));
  for (int u = 0; u < kU; ++u) theta1_jet[u] = Jet(theta1[u], u);
  const auto oracle = [&] {
    test::direct_ml_residuals(problem, *scenario.model, theta1_jet.data(), 0, 300,
                              residuals.data());
  };
  oracle();
  Eigen::MatrixXd J_auto(problem.num_residuals(), kU);
  Eigen::VectorXd r_auto(problem.num_residuals());
  for (Eigen::Index row = 0; row < problem.num_residuals(); ++row) {
    r_auto[row] = residuals[row].a;
    J_auto.row(row) = residuals[row].v.transpose();
  }
  EXPECT_LT((r - r_auto).lpNorm<Eigen::Infinity>(), 1e-12 * r_auto.lpNorm<Eigen::Infinity>());
  for (int u = 0; u < kU; ++u) {
    const double scale = J_auto.col(u).lpNorm<Eigen::Infinity>();
    EXPECT_LT((J.col(u) - J_auto.col(u)).lpNorm<Eigen::Infinity>(), 1e-12 * scale) << unknown[u];
  }
  // Central differences (relative step 1e-6), over residuals away from an efficiency switch:
  // rows whose tau'_G dq_M changes sign within the step are not smooth and are skipped.
  int compared = 0;
  for (int u = 0; u < kU; ++u) {
    const double h = 1e-6 * std::max(1.0, std::abs(theta1[u]));
    Eigen::VectorXd plus = theta1, minus = theta1, rp, rm;
    plus[u] += h;
    minus[u] -= h;
    problem.evaluate(plus, rp, nullptr);
    problem.evaluate(minus, rm, nullptr);
    const Eigen::VectorXd fd = (rp - rm) / (2 * h);
    const double scale = std::max(1.0, J.col(u).lpNorm<Eigen::Infinity>());
    for (Eigen::Index k = 0; k < fd.size(); ++k) {
      const double second = std::abs(rp[k] + rm[k] - 2 * r[k]);
      if (second > 1e-6) continue;  // a kink inside the step
      EXPECT_NEAR(J(k, u), fd[k], 1e-8 * scale) << unknown[u] << " residual " << k;
      ++compared;
    }
  }
  EXPECT_GT(compared, 22 * 1200 * 99 / 100);

  // Speed of the analytic Jacobian against automatic differentiation (printed, not asserted).
  const auto time = [](auto&& f) {
    const auto start = std::chrono::steady_clock::now();
    for (int repeat = 0; repeat < 20; ++repeat) f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / 20;
  };
  const double analytic = time([&] { problem.evaluate(theta1, r, &J); });
  const double automatic = time(oracle);
  std::printf(
      "residuals + Jacobian, 300 samples x 4 axes x 22 unknowns: analytic %.3g ms, "
      "autodiff %.3g ms\n",
      analytic * 1e3, automatic * 1e3);
}

TEST(MlFit, Approach3RecoversTheLoadOfTable2) {
  Scenario scenario(true);
  MlSetup setup;
  setup.unknown = scenario.unknowns({2, 3, 4, 5});
  setup.payload_link = 7;
  MlProblem problem(*scenario.model, {scenario.data}, setup, scenario.start(setup.unknown));
  const auto start = std::chrono::steady_clock::now();
  const MlFitResult fit = fit_ml(problem);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "approach 3: %d LM iterations, %.3f s in Ceres (%.2f ms per iteration), %.3f s "
      "with the linear guess and statistics\n%s\n",
      fit.iterations, fit.solve_seconds, 1e3 * fit.solve_seconds / std::max(1, fit.iterations),
      seconds, fit.solver_report.c_str());
  EXPECT_EQ(fit.identifiability.rank, 22);
  EXPECT_TRUE(fit.identifiability.directions.empty());
  EXPECT_TRUE(std::isfinite(fit.identifiability.condition_number));
  std::printf("condition number at the initial guess %.3g\n", fit.identifiability.condition_number);
  ASSERT_TRUE(fit.has_load);
  for (const std::string& note : fit.notes) std::printf("note: %s\n", note.c_str());
  EXPECT_TRUE(fit.load_warnings.empty());
  // Table 2, approach 3 column: average errors of the real experiments.
  const LoadParameters exact = test::table2_load();
  const double bound[10] = {0.85, 0.001, 0.002, 0.004, 0.70, 1.72, 0.39, 0.26, 0.34, 0.18};
  const auto estimate = fit.load.to_vector(), truth = exact.to_vector(),
             sd = fit.load_std_dev.to_vector();
  for (int k = 0; k < kLoadParams; ++k) {
    std::printf("%-9s exact %9.4f estimate %9.4f (sd %.2g)  initial %9.4f\n",
                load_param_names()[k].c_str(), truth[k], estimate[k], sd[k], fit.initial[k]);
    EXPECT_NEAR(estimate[k], truth[k], bound[k]) << load_param_names()[k];
    // The standard deviations describe the errors (5 sigma).
    EXPECT_LT(std::abs(estimate[k] - truth[k]), 5 * sd[k]) << load_param_names()[k];
  }
  // Efficiencies and friction of the moving axes.
  for (int u = kLoadParams; u < 22; ++u) {
    const auto k = std::find(scenario.names.begin(), scenario.names.end(), fit.names[u]) -
                   scenario.names.begin();
    EXPECT_NEAR(fit.value[u], scenario.truth[k], 5 * fit.std_dev[u]) << fit.names[u];
  }
  // The residuals are the noise: rms error per axis near its sigma.
  for (const int i : {2, 3, 4, 5}) EXPECT_NEAR(fit.rms_error[i], kSigma[i], 0.1 * kSigma[i]) << i;
  EXPECT_NEAR(fit.residual_std_dev, 1.0, 0.05);
}

TEST(MlFit, WristOnlyLeavesTheLoadMassUnidentifiable) {
  Scenario scenario(false);
  MlSetup setup;
  setup.unknown = scenario.unknowns({3, 4, 5});
  setup.payload_link = 7;
  MlProblem problem(*scenario.model, {scenario.data}, setup, scenario.start(setup.unknown));
  EXPECT_EQ(problem.axes(), (std::vector<int>{3, 4, 5}));  // axis 3 does not move
  ASSERT_EQ(problem.num_unknowns(), 19);
  const MlFitResult fit = fit_ml(problem);
  EXPECT_EQ(fit.identifiability.rank, 18);
  ASSERT_EQ(fit.identifiability.directions.size(), 1u);
  const std::string& direction = fit.identifiability.directions[0];
  std::printf("%s\n", direction.c_str());
  EXPECT_EQ(direction.rfind("load_m (", 0), 0u) << direction;
  EXPECT_TRUE(std::isnan(fit.value[0]));
  EXPECT_TRUE(std::isnan(fit.std_dev[0]));
  EXPECT_TRUE(std::isnan(fit.load.mass));
  EXPECT_FALSE(fit.identifiability.identifiable[0]);
}

TEST(MlProblem, BadSetupsAreNamed) {
  Scenario scenario(true, 50);
  MlSetup setup;
  setup.unknown = {"load_m", "Rz9"};
  setup.payload_link = 7;
  const auto message = [&](MlSetup s, const std::vector<MlExperiment>& data) -> std::string {
    try {
      MlProblem problem(*scenario.model, data, s, scenario.truth);
    } catch (const EstimationError& error) {
      return error.what();
    }
    return "no error";
  };
  EXPECT_NE(message(setup, {scenario.data}).find("unknown parameter 'Rz9'"), std::string::npos);
  setup.unknown = {"load_m", "load_m"};
  EXPECT_NE(message(setup, {scenario.data}).find("'load_m' is listed twice"), std::string::npos);
  setup.unknown = {"load_m"};
  setup.payload_link = 0;
  EXPECT_NE(message(setup, {scenario.data}).find("no payload link"), std::string::npos);
  setup.payload_link = 9;
  EXPECT_NE(message(setup, {scenario.data}).find("payload link 9 has no parameter 'XX9'"),
            std::string::npos);
  setup.payload_link = 7;
  MlExperiment bad = scenario.data;
  bad.tau_M(7, 3) = std::nan("");
  EXPECT_EQ(message(setup, {bad}).find("axes3-6: sample 7 (column tau_M4): error:"), 0u)
      << message(setup, {bad});
  bad = scenario.data;
  bad.sigma[4] = 0;
  EXPECT_NE(message(setup, {bad}).find("noise standard deviation of axis 5"), std::string::npos);
}

TEST(MlExperiment, FromPeriodicPreparedExperiment) {
  // K = diag(2, 4): tau_joint = K^T tau_M, so tau_M = tau_joint / ratio and its noise standard
  // deviation the joint-side one over the ratio.
  DriveChain drive = DriveChain::identity(2);
  drive.motor_from_joint = Eigen::Vector2d(2, 4).asDiagonal();
  PreparedExperiment prepared;
  prepared.data.source = "run.csv";
  prepared.data.q = Eigen::MatrixXd::Random(5, 2);
  prepared.data.dq = Eigen::MatrixXd::Random(5, 2);
  prepared.data.ddq = Eigen::MatrixXd::Random(5, 2);
  prepared.data.tau = Eigen::MatrixXd::Random(5, 2);
  prepared.tau_noise_variance = Eigen::Vector2d(9, 16);
  const MlExperiment x = ml_experiment(prepared, drive);
  EXPECT_EQ(x.source, "run.csv");
  EXPECT_TRUE(x.q == prepared.data.q);
  EXPECT_NEAR((x.tau_M.col(0) - prepared.data.tau.col(0) / 2).norm(), 0, 1e-15);
  EXPECT_NEAR((x.tau_M.col(1) - prepared.data.tau.col(1) / 4).norm(), 0, 1e-15);
  EXPECT_NEAR(x.sigma[0], 1.5, 1e-15);
  EXPECT_NEAR(x.sigma[1], 1.0, 1e-15);
  prepared.tau_noise_variance.resize(0);
  try {
    ml_experiment(prepared, drive);
    FAIL() << "expected EstimationError";
  } catch (const EstimationError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("run.csv: error: no torque noise variance", 0), 0u)
        << error.what();
  }
}

// The linear route (section 3.2, approach 1 of section 4) on the scenario's motion with data
// remade: `efficiency_one` gives the motor torques of the same truth with every R_z = 1, plus the
// scenario's noise when `noise`. From MlProblem::torque_errors: measured - model.
struct LinearScenario {
  Scenario scenario{true};
  std::vector<std::string> unknown;  // approach 1: the load, Rv and Rc of axes 3-6
  Eigen::VectorXd truth;             // scenario.truth with R_z = 1
  MlExperiment data;

  explicit LinearScenario(bool noise) {
    for (const std::string& name : scenario.unknowns({2, 3, 4, 5})) {
      if (name.compare(0, 2, "Rz") != 0) unknown.push_back(name);
    }
    truth = scenario.truth;
    for (size_t k = 0; k < scenario.names.size(); ++k) {
      if (scenario.names[k].compare(0, 2, "Rz") == 0) truth[static_cast<Eigen::Index>(k)] = 1;
    }
    MlSetup setup = this->setup();
    MlProblem problem(*scenario.model, {scenario.data}, setup, truth);
    data = scenario.data;
    data.tau_M -= problem.torque_errors(truth);                      // model torques with R_z = 1
    if (noise) data.tau_M += problem.torque_errors(scenario.truth);  // the noise
  }

  MlSetup setup() const {
    MlSetup s;
    s.unknown = unknown;
    s.payload_link = 7;
    return s;
  }

  // The known values (R_z = 1) and a starting point far from the truth for the unknowns.
  Eigen::VectorXd start() const {
    Eigen::VectorXd values = scenario.start(unknown);
    for (size_t k = 0; k < scenario.names.size(); ++k) {
      if (scenario.names[k].compare(0, 2, "Rz") == 0) values[static_cast<Eigen::Index>(k)] = 1;
    }
    return values;
  }
};

TEST(LinearRoute, RecoversTheLoadFromNoiseFreeDataWithUnitEfficiencies) {
  LinearScenario linear(false);
  MlProblem problem(*linear.scenario.model, {linear.data}, linear.setup(), linear.start());
  const LinearRoute route = linear_route(problem);
  std::printf("linear model: %d parameters excited, %d base parameters\n", route.excited_parameters,
              route.base_parameters);
  EXPECT_LT(route.base_parameters, route.excited_parameters);  // regrouping happened
  const MlFitResult& fit = route.fit;
  // Approach 1's unknowns: the load, Rv and Rc of axes 3-6, then the rotor inertias JM3-JM6.
  ASSERT_EQ(fit.names.size(), 22u);
  EXPECT_EQ(fit.names[18], "JM3");
  EXPECT_EQ(fit.identifiability.rank, 22) << fit.identifiability.directions.size();
  ASSERT_TRUE(fit.has_load);
  const auto estimate = fit.load.to_vector(), truth = test::table2_load().to_vector();
  for (int k = 0; k < kLoadParams; ++k) {
    EXPECT_NEAR(estimate[k], truth[k], 1e-7 * (1 + std::abs(truth[k]))) << load_param_names()[k];
  }
  for (size_t u = kLoadParams; u < fit.names.size(); ++u) {
    const auto k =
        std::find(linear.scenario.names.begin(), linear.scenario.names.end(), fit.names[u]) -
        linear.scenario.names.begin();
    EXPECT_NEAR(fit.value[static_cast<Eigen::Index>(u)], linear.truth[k], 1e-6 * linear.truth[k])
        << fit.names[u];
  }
  for (const int i : {2, 3, 4, 5}) EXPECT_LT(fit.rms_error[i], 1e-8) << i;
  // The starting point handed to the nonlinear search carries the same unknowns.
  for (int u = 0; u < problem.num_unknowns(); ++u) {
    const int k = problem.unknown_indices()[u];
    EXPECT_NEAR(route.values[k], linear.truth[k], 1e-6 * (1 + std::abs(linear.truth[k])))
        << problem.unknown_names()[u];
  }
}

TEST(LinearRoute, StandardDeviationsDescribeTheErrorsWithUnitEfficiencies) {
  LinearScenario linear(true);
  MlProblem problem(*linear.scenario.model, {linear.data}, linear.setup(), linear.start());
  const MlFitResult fit = linear_route(problem).fit;
  const auto estimate = fit.load.to_vector(), truth = test::table2_load().to_vector(),
             sd = fit.load_std_dev.to_vector();
  for (int k = 0; k < kLoadParams; ++k) {
    std::printf("%-9s exact %9.4f approach 1 %9.4f (sd %.2g)\n", load_param_names()[k].c_str(),
                truth[k], estimate[k], sd[k]);
    EXPECT_LT(std::abs(estimate[k] - truth[k]), 4 * sd[k]) << load_param_names()[k];
  }
  // The linear model's residuals are the noise.
  for (const int i : {2, 3, 4, 5}) EXPECT_NEAR(fit.rms_error[i], kSigma[i], 0.1 * kSigma[i]) << i;
}

// Swevers Tables 2 and 3: with efficiencies below 1, approach 1 (linear, R_z = 1) gets the load
// wrong by far more than approach 3 (R_z unknown), while its many parameters fit the torques at
// least as well as approach 2 (the physical model with R_z = 1): approach 2's model is approach
// 1's with the link values fixed, so its weighted residual cannot be smaller.
TEST(LinearRoute, Approach1IsBiasedButFitsTheTorquesBetterThanApproach2) {
  Scenario scenario(true);
  LinearScenario linear(false);  // for approach 1's unknowns and R_z = 1 values
  MlProblem problem(*scenario.model, {scenario.data}, linear.setup(), linear.start());
  const LinearRoute approach1 = linear_route(problem);
  const MlFitResult approach2 = fit_ml(problem);
  MlSetup setup3 = linear.setup();
  setup3.unknown = scenario.unknowns({2, 3, 4, 5});
  MlProblem problem3(*scenario.model, {scenario.data}, setup3, scenario.start(setup3.unknown));
  const MlFitResult approach3 = fit_ml(problem3);
  const auto truth = test::table2_load().to_vector(), load1 = approach1.fit.load.to_vector(),
             load2 = approach2.load.to_vector(), load3 = approach3.load.to_vector(),
             sd3 = approach3.load_std_dev.to_vector();
  std::printf("load errors (estimate - exact): approach 1, approach 2, approach 3 (sd)\n");
  for (int k = 0; k < kLoadParams; ++k) {
    std::printf("%-9s %10.4f %10.4f %10.4f (%.2g)\n", load_param_names()[k].c_str(),
                load1[k] - truth[k], load2[k] - truth[k], load3[k] - truth[k], sd3[k]);
  }
  const double error1 = std::abs(load1[0] - truth[0]), error3 = std::abs(load3[0] - truth[0]);
  EXPECT_GT(error1, 10 * error3) << "mass";
  EXPECT_GT(error1, 10 * sd3[0]) << "mass";
  double weighted1 = 0, weighted2 = 0;
  for (const int i : {2, 3, 4, 5}) {
    std::printf("axis %d rms error: approach 1 %.3f, approach 2 %.3f, approach 3 %.3f N m\n", i + 1,
                approach1.fit.rms_error[i], approach2.rms_error[i], approach3.rms_error[i]);
    weighted1 += std::pow(approach1.fit.rms_error[i] / kSigma[i], 2);
    weighted2 += std::pow(approach2.rms_error[i] / kSigma[i], 2);
  }
  EXPECT_LT(weighted1, weighted2);
}

TEST(LinearRoute, WristOnlyNamesTheLoadMass) {
  Scenario scenario(false);
  MlSetup setup;
  for (const std::string& name : scenario.unknowns({3, 4, 5})) {
    if (name.compare(0, 2, "Rz") != 0) setup.unknown.push_back(name);
  }
  setup.payload_link = 7;
  MlProblem problem(*scenario.model, {scenario.data}, setup, scenario.start(setup.unknown));
  const MlFitResult fit = linear_route(problem).fit;
  ASSERT_FALSE(fit.identifiability.directions.empty());
  for (const std::string& direction : fit.identifiability.directions) {
    std::printf("%s\n", direction.c_str());
  }
  EXPECT_FALSE(fit.identifiability.identifiable[0]) << "load_m";
  EXPECT_TRUE(std::isnan(fit.load.mass));
}

// Only motor 6 fitted: its torque alone cannot separate the ten load parameters, friction and
// rotor inertia (fewer identifiable combinations than unknowns); the route names what is
// missing instead of failing, and reports no number for it.
TEST(LinearRoute, OneMotorLeavesDirectionsUndetermined) {
  Scenario scenario(true);
  MlSetup setup;
  setup.unknown = load_param_names();
  for (const char* name : {"Rv6", "Rc6"}) setup.unknown.push_back(name);
  setup.payload_link = 7;
  setup.axes = {5};
  MlProblem problem(*scenario.model, {scenario.data}, setup, scenario.start(setup.unknown));
  const LinearRoute route = linear_route(problem);
  std::printf("motor 6 alone: %d base parameters for %zu unknowns, rank %d\n",
              route.base_parameters, route.fit.names.size(), route.fit.identifiability.rank);
  EXPECT_LT(route.fit.identifiability.rank, static_cast<int>(route.fit.names.size()));
  EXPECT_FALSE(route.fit.identifiability.directions.empty());
  for (size_t u = 0; u < route.fit.names.size(); ++u) {
    EXPECT_EQ(std::isnan(route.fit.value[static_cast<Eigen::Index>(u)]),
              !route.fit.identifiability.identifiable[u])
        << route.fit.names[u];
  }
  EXPECT_TRUE(route.values.allFinite());
}

}  // namespace
}  // namespace modelgen
