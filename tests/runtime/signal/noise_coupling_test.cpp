// The independence test of the position and torque errors of a periodic record
// (modelgen/signal/noise_coupling.hpp) on records simulated here: independent noise, white or
// coloured by a filter, stays near N(0, 1) over many seeds and never reaches the refusal
// bound; a PD-like response of the torque to the position noise is found with the
// correlation computed here in closed form; exact positions leave nothing to test.

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/signal/noise_coupling.hpp"
#include "modelgen/signal/period.hpp"

#include "tests/runtime/signal/signal_test_support.hpp"

namespace modelgen {
namespace {

using namespace signal_test;  // tests/runtime/signal/signal_test_support.hpp

constexpr double kPeriod = 2.0, kDt = 0.002;  // N = 1000

// White Gaussian noise, one column per axis.
Eigen::MatrixXd white(Eigen::Index rows, Eigen::Index cols, double sigma, std::mt19937_64& engine) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(rows, cols);
  add_noise(m, sigma, engine);
  return m;
}

// A first-order low-pass y_k = a y_k-1 + (1 - a) x_k along each column: noise correlated over
// about 1 / (1 - a) samples.
Eigen::MatrixXd low_pass(const Eigen::MatrixXd& x, double a) {
  Eigen::MatrixXd y = x;
  for (Eigen::Index k = 1; k < y.rows(); ++k) y.row(k) = a * y.row(k - 1) + (1 - a) * x.row(k);
  return y;
}

// The three-axis excitation over `periods` periods with the errors `q_error`, `tau_error`.
Trajectory record(int periods, const Eigen::MatrixXd& q_error, const Eigen::MatrixXd& tau_error) {
  Trajectory x = sample(three_axis_excitation(kPeriod), kDt, periods * kPeriod);
  x.source = "record.csv";
  x.has_velocity = false;
  x.tau = torque_of(x) + tau_error.topRows(x.t.size());
  x.q += q_error.topRows(x.t.size());
  return x;
}

TEST(NoiseCoupling, IndependentNoiseStaysNearTheNullOverSeeds) {
  // 20 seeds x 3 axes x 2 colours x 2 period counts = 240 tests of a N(0, 1) score: a few
  // beyond 2.5 are expected, none beyond the refusal bound 5 (one in 3e6).
  double sum = 0, sum_sq = 0, largest_correlation = 0;
  int count = 0, beyond = 0;
  for (int seed = 1; seed <= 20; ++seed) {
    for (const int periods : {3, 8}) {
      for (const double a : {0.0, 0.9}) {
        std::mt19937_64 engine(seed);
        const Eigen::Index n = static_cast<Eigen::Index>(periods * kPeriod / kDt) + 1;
        const Eigen::MatrixXd q_error = low_pass(white(n, 3, 1e-3, engine), a);
        const Eigen::MatrixXd tau_error = low_pass(white(n, 3, 0.3, engine), a * a);
        const NoiseCoupling c =
            noise_coupling(average_periods(record(periods, q_error, tau_error), kPeriod));
        ASSERT_EQ(c.z.size(), 3);
        EXPECT_EQ(c.degrees, c.lines_per_band * (periods - 1));
        for (int j = 0; j < 3; ++j) {
          EXPECT_EQ(c.bands[j], 499 / c.lines_per_band);
          EXPECT_LT(c.z[j], 5.0) << seed << " " << periods << " " << a << " " << j;
          largest_correlation = std::max(largest_correlation, c.correlation[j]);
          sum += c.z[j];
          sum_sq += c.z[j] * c.z[j];
          beyond += c.z[j] > 2.5;
          ++count;
        }
      }
    }
  }
  const double mean = sum / count, sd = std::sqrt(sum_sq / count - mean * mean);
  // The mean of 240 N(0, 1) scores has sd 0.065; their sd is 1 within about 5 % each way.
  EXPECT_NEAR(mean, 0.0, 0.3);
  EXPECT_NEAR(sd, 1.0, 0.2);
  EXPECT_LE(beyond, 6);  // 240 x 0.0062 = 1.5 expected
  // The bias-corrected correlation's own noise: its square averages 62-166 band coherences of
  // sd 0.06 each (fewer in effect where a colour puts the energy in few bands).
  EXPECT_LT(largest_correlation, 0.25);
  std::cout << "z over " << count << " tests: mean " << mean << ", sd " << sd << ", " << beyond
            << " beyond 2.5; largest correlation " << largest_correlation << "\n";
}

TEST(NoiseCoupling, APdResponseToThePositionNoiseIsFoundWithItsCorrelation) {
  // tau error = -(kp e_k + kd (e_k - e_k-1) / dt) + w_k, e and w white (sigma_e, sigma_w):
  // the response has variance ((kp + c)^2 + c^2) sigma_e^2 with c = kd / dt, so the
  // correlation of the torque error with it is sqrt(var_r / (var_r + sigma_w^2)).
  const int periods = 4;
  const double sigma_e = 1e-4, kp = 500, kd = 0.2, c = kd / kDt;
  const Eigen::Index n = static_cast<Eigen::Index>(periods * kPeriod / kDt) + 1;
  const double var_r = ((kp + c) * (kp + c) + c * c) * sigma_e * sigma_e;
  for (const double sigma_w : {0.02, 0.05, 0.2}) {
    std::mt19937_64 engine(42);
    const Eigen::MatrixXd e = white(n, 3, sigma_e, engine);
    Eigen::MatrixXd tau_error = white(n, 3, sigma_w, engine);
    for (Eigen::Index k = 1; k < n; ++k) {
      tau_error.row(k) -= kp * e.row(k) + c * (e.row(k) - e.row(k - 1));
    }
    const NoiseCoupling coupling =
        noise_coupling(average_periods(record(periods, e, tau_error), kPeriod));
    const double expected = std::sqrt(var_r / (var_r + sigma_w * sigma_w));
    for (int j = 0; j < 3; ++j) {
      // 83 bands of 6 lines: the correlation's estimate is good to a few hundredths.
      EXPECT_NEAR(coupling.correlation[j], expected, 0.04) << sigma_w << " " << j;
      EXPECT_GT(coupling.z[j], 5.0) << sigma_w << " " << j;
    }
  }
}

TEST(NoiseCoupling, TheCrossCovarianceOfAProportionalErrorIsItsGainTimesTheVariance) {
  // tau error = -3 q error exactly: every line's cross-covariance is -3 V_q and V_tau = 9 V_q.
  std::mt19937_64 engine(5);
  const Eigen::Index n = static_cast<Eigen::Index>(3 * kPeriod / kDt) + 1;
  const Eigen::MatrixXd e = white(n, 3, 1e-3, engine);
  const PeriodicAverage average = average_periods(record(3, e, -3.0 * e), kPeriod);
  const Eigen::MatrixXd& v = average.q_line_variance;
  EXPECT_LT((average.tau_q_line_covariance.real() + 3.0 * v).cwiseAbs().maxCoeff(),
            1e-9 * v.maxCoeff());
  EXPECT_LT(average.tau_q_line_covariance.imag().cwiseAbs().maxCoeff(), 1e-9 * v.maxCoeff());
  EXPECT_LT((average.tau_line_variance - 9.0 * v).cwiseAbs().maxCoeff(), 1e-9 * v.maxCoeff());
}

TEST(NoiseCoupling, ExactPositionsLeaveNothingToTest) {
  std::mt19937_64 engine(3);
  const Eigen::Index n = static_cast<Eigen::Index>(3 * kPeriod / kDt) + 1;
  const NoiseCoupling c = noise_coupling(
      average_periods(record(3, Eigen::MatrixXd::Zero(n, 3), white(n, 3, 0.3, engine)), kPeriod));
  for (int j = 0; j < 3; ++j) {
    EXPECT_EQ(c.bands[j], 0) << j;
    EXPECT_EQ(c.z[j], 0.0) << j;
  }
}

}  // namespace
}  // namespace modelgen
