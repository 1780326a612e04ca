// identify() with the parallel decimation (Gautier & Briot eq. 13-14) against the same
// equations stacked here by hand: each experiment's regressor rows and torques built sample by
// sample, each joint's rows decimated column by column with decimate(), the PIM's power rows
// from power_regressor() (identify derives them from the IDIM rows), then fit_wls on the
// stack. Experiments with and without decimation are mixed.

#include <cmath>
#include <iostream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "generated/tx40/tx40.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/estimation/least_squares.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/signal/decimation.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

const GeneratedModel<tx40::Model> kModel;

// A noisy TX-40 experiment: 3-harmonic excitation, torques from random base parameters.
Trajectory experiment(const Eigen::VectorXd& beta, int seed, double sample_time, double duration) {
  test::Random random(seed);
  FourierTrajectory f;
  f.period = 5.0;
  f.q0 = random.vector(6, -0.5, 0.5);
  f.a = Eigen::MatrixXd(6, 3);
  f.b = Eigen::MatrixXd(6, 3);
  for (int j = 0; j < 6; ++j) {
    for (int l = 0; l < 3; ++l)
      f.a(j, l) = random.uniform(-0.8, 0.8), f.b(j, l) = random.uniform(-0.8, 0.8);
  }
  Trajectory x = sample(f, sample_time, duration);
  x.source = "experiment" + std::to_string(seed);
  for (Eigen::Index s = 0; s < x.t.size(); ++s) {
    const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
    Eigen::VectorXd tau(6);
    kModel.inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau.data());
    x.tau.row(s) = tau.transpose() + 0.5 * random.vector(6, -1, 1).transpose();
  }
  return x;
}

struct Stack {
  Eigen::MatrixXd W;
  Eigen::VectorXd y;
  std::vector<int> group;
};

// Appends experiment e's equations, decimated by `factor`, as identify() is documented to.
// With `min_speed` (a speed per joint), the rows where a joint is slower are left out: for a
// decimated experiment judged on dq decimated like the equations.
void append(Stack& stack, const Trajectory& x, int e, int factor, bool power,
            const std::vector<double>& min_speed = {}) {
  const int n = 6, nb = kModel.num_base_params();
  const Eigen::Index m = x.t.size();
  Eigen::MatrixXd rows(power ? m : m * n, nb);
  Eigen::VectorXd y(power ? m : m * n);
  std::vector<double> W(n * nb), h(nb);
  for (Eigen::Index s = 0; s < m; ++s) {
    const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
    if (power) {
      kModel.power_regressor(q.data(), dq.data(), ddq.data(), h.data());
      for (int b = 0; b < nb; ++b) rows(s, b) = h[b];
      y[s] = dq.dot(x.tau.row(s).transpose());
    } else {
      kModel.regressor(q.data(), dq.data(), ddq.data(), W.data());
      // Joint-major blocks here (all samples of joint 1, then joint 2, ...).
      for (int j = 0; j < n; ++j) {
        for (int b = 0; b < nb; ++b) rows(j * m + s, b) = W[j * nb + b];
        y[j * m + s] = x.tau(s, j);
      }
    }
  }
  if (factor > 1 && !power && !min_speed.empty()) {
    // Before the decimation, equation j of a sample where joint j, or a motor driving it
    // (K(k, j) != 0, its speed K.row(k) dq / K(k, k)), is slow weighs 0 on both sides
    // (no guard: the test's positions are exact).
    const Eigen::MatrixXd& K = kModel.drive_chain().motor_from_joint;
    for (Eigen::Index s = 0; s < m; ++s) {
      const Eigen::VectorXd dq = x.dq.row(s).transpose();
      for (int j = 0; j < n; ++j) {
        bool slow = std::abs(dq[j]) < min_speed[static_cast<std::size_t>(j)];
        for (int k = 0; k < n; ++k) {
          if (K(k, j) == 0) continue;
          slow =
              slow || std::abs(K.row(k).dot(dq) / K(k, k)) < min_speed[static_cast<std::size_t>(k)];
        }
        if (!slow) continue;
        rows.row(j * m + s).setZero();
        y[j * m + s] = 0;
      }
    }
  }
  const int blocks = power ? 1 : n;
  for (int j = 0; j < blocks; ++j) {
    // Decimated, only the rows clear of the filter's edges are equations.
    const Eigen::MatrixXd Wj = factor > 1 ? decimate_interior(rows.middleRows(j * m, m), factor)
                                          : Eigen::MatrixXd(rows.middleRows(j * m, m));
    const Eigen::MatrixXd yj = factor > 1 ? decimate_interior(y.segment(j * m, m), factor)
                                          : Eigen::MatrixXd(y.segment(j * m, m));
    const Eigen::MatrixXd dq = factor > 1 ? decimate_interior(x.dq, factor) : x.dq;
    std::vector<Eigen::Index> kept;
    for (Eigen::Index r = 0; r < Wj.rows(); ++r) {
      bool slow = false;
      for (std::size_t k = 0; k < min_speed.size(); ++k) {
        slow = slow || std::abs(dq(r, static_cast<Eigen::Index>(k))) < min_speed[k];
      }
      if (!slow) kept.push_back(r);
    }
    const auto count = static_cast<Eigen::Index>(kept.size());
    const Eigen::Index r0 = stack.W.rows();
    stack.W.conservativeResize(r0 + count, nb);
    stack.y.conservativeResize(r0 + count);
    stack.W.bottomRows(count) = Wj(kept, Eigen::all);
    stack.y.tail(count) = yj(kept, 0);
    for (Eigen::Index r = 0; r < count; ++r) stack.group.push_back(power ? e : e * n + j);
  }
}

// Eq. 18's sd on the stacked equations, to round-off; but the decimation filter leaves the
// decimated white noise a small correlation from row to row (its lag-1 autocorrelation
// significant over 6 000 rows), which identify's sandwich covariance takes into account and
// names: then the sd may differ from eq. 18's by a few percent.
double sd_tolerance(const std::string& covariance) {
  std::cout << "covariance: " << (covariance.empty() ? "eq. 18" : covariance) << "\n";
  return covariance.empty() ? 1e-7 : 3e-2;
}

class IdentifyDecimation : public testing::TestWithParam<Method> {};

TEST_P(IdentifyDecimation, EqualsTheEquationsStackedByHand) {
  const Method method = GetParam();
  const bool power = method == Method::kPimWls;
  test::Random random(5);
  const Eigen::VectorXd beta = random.vector(kModel.num_base_params(), -2, 2);
  const std::vector<Trajectory> data = {experiment(beta, 1, 0.002, 10.0),
                                        experiment(beta, 2, 0.002, 10.0),
                                        experiment(beta, 3, 0.01, 10.0)};
  const std::vector<int> factors = {5, 1, 3};
  IdentifyOptions options;
  options.decimation = factors;
  const Identification id = identify(kModel, data, method, options);

  Stack stack;
  stack.W.resize(0, kModel.num_base_params());
  for (int e = 0; e < 3; ++e) append(stack, data[e], e, factors[e], power);
  const LeastSquaresResult expected =
      method == Method::kOls ? fit_ols(stack.W, stack.y, kModel.base_param_names())
                             : fit_wls(stack.W, stack.y, stack.group, kModel.base_param_names());
  // The fitted equations agree whatever the conditioning; the parameters themselves only as
  // far as the condition number lets round-off through (a single PIM trajectory identifies
  // the wrist poorly, Gautier & Briot section IV: there only the fit is compared).
  // PIM-WLS: one experiment's own power equations (eq. 20's OLS per group) are nearly
  // rank-deficient, so its sigma depends on rank decisions at the 1e-10 level that a
  // different order of reduction (two threads, merged) can take differently: here the
  // weights, and so the estimates, agree to a few 1e-3 only; the IDIM's to round-off.
  const double tolerance = power ? 1e-2 : 1e-9;
  EXPECT_LT(test::relative_error(stack.W * id.fit.value, stack.W * expected.value, 1.0), tolerance);
  // PIM-WLS's residual sd follows those weights further: a last-bit change of the generated
  // power regressor moved it by 3 % (2026-12-02), so 5 % there.
  EXPECT_NEAR(id.fit.residual_std_dev, expected.residual_std_dev,
              (power ? 5e-2 : tolerance) * expected.residual_std_dev);
  if (!power) {
    EXPECT_LT(test::relative_error(id.fit.value, expected.value, 1.0), 1e-9);
    EXPECT_LT(test::relative_error(id.fit.std_dev, expected.std_dev, 1.0),
              sd_tolerance(id.fit.covariance));
  }
  // Rows used: 5000 / 5, 5000 and 1000 / 3 samples (per joint for the IDIM), less the
  // decimated rows at the edges.
  EXPECT_EQ(id.samples, decimated_interior(5000, 5).count + 5000 + decimated_interior(1000, 3).count);
  EXPECT_LT(decimated_interior(5000, 5).count, decimated_rows(5000, 5));
  // Against a fit without decimation the estimates differ (the filter changed the equations),
  // so the comparison above can fail.
  const Identification plain = identify(kModel, data, method);
  EXPECT_GT(test::relative_error(plain.fit.value, id.fit.value, 1.0), 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Methods, IdentifyDecimation,
                         testing::Values(Method::kOls, Method::kWls, Method::kPimWls));

TEST(IdentifyDecimation, MinSpeedLeavesOutTheSlowRowsAfterTheDecimation) {
  test::Random random(6);
  const Eigen::VectorXd beta = random.vector(kModel.num_base_params(), -2, 2);
  const std::vector<Trajectory> data = {experiment(beta, 1, 0.002, 10.0),
                                        experiment(beta, 2, 0.002, 10.0)};
  const std::vector<int> factors = {5, 1};
  const std::vector<double> min_speed = {0.3, 0.2, 0.2, 0.1, 0.1, 0.1};
  IdentifyOptions options;
  options.decimation = factors;
  options.min_speed = min_speed;
  const Identification id = identify(kModel, data, Method::kWls, options);
  Stack stack;
  stack.W.resize(0, kModel.num_base_params());
  for (int e = 0; e < 2; ++e) append(stack, data[e], e, factors[e], false, min_speed);
  const LeastSquaresResult expected =
      fit_wls(stack.W, stack.y, stack.group, kModel.base_param_names());
  EXPECT_LT(test::relative_error(id.fit.value, expected.value, 1.0), 1e-9);
  EXPECT_LT(test::relative_error(id.fit.std_dev, expected.std_dev, 1.0),
            sd_tolerance(id.fit.covariance));
  const Eigen::Index all = decimated_interior(5000, 5).count + 5000;
  EXPECT_EQ(id.samples, stack.W.rows() / 6);
  EXPECT_EQ(id.samples + id.slow_samples, all);
  EXPECT_GT(id.slow_samples, all / 20);  // the joints reverse: some rows go
  // A speed no sample reaches: refused, naming the experiment and its speeds.
  options.min_speed.assign(6, 100.0);
  try {
    identify(kModel, data, Method::kWls, options);
    ADD_FAILURE() << "a minimum speed that leaves nothing was accepted";
  } catch (const EstimationError& e) {
    EXPECT_NE(std::string(e.what()).find("leaves out every"), std::string::npos) << e.what();
  }
  options.min_speed = {0.1};
  EXPECT_THROW(identify(kModel, data, Method::kWls, options), EstimationError);
}

TEST(IdentifyDecimation, FactorsAreChecked) {
  test::Random random(5);
  const Eigen::VectorXd beta = random.vector(kModel.num_base_params(), -2, 2);
  const std::vector<Trajectory> data = {experiment(beta, 1, 0.01, 10.0)};
  IdentifyOptions options;
  options.decimation = {2, 2};
  EXPECT_THROW(identify(kModel, data, Method::kWls, options), EstimationError);
  options.decimation = {0};
  EXPECT_THROW(identify(kModel, data, Method::kWls, options), EstimationError);
  // 1000 samples by 100: 10 equations per joint, too few for WLS; the message names the file
  // and joint and points at the decimation.
  options.decimation = {100};
  try {
    identify(kModel, data, Method::kWls, options);
    ADD_FAILURE() << "a too strong decimation was accepted";
  } catch (const EstimationError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("experiment1"), std::string::npos) << what;
    EXPECT_NE(what.find("decimated: experiment1 by 100"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace modelgen
