// Period detection and averaging (modelgen/signal/period.hpp): the average and its noise
// variance against the trajectory and noise they were simulated with (Swevers 2002, eq. 15-17),
// the detected period of multi-sines, and a real Franka Panda record.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/QR>

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/signal/period.hpp"

#include "tests/runtime/signal/signal_test_support.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using namespace signal_test;  // tests/runtime/signal/signal_test_support.hpp

TEST(AveragePeriods, AveragesAndNoiseVarianceMatchTheSimulatedNoise) {
  const double period = 2.0, dt = 0.002;  // N = 1000
  const int periods = 10;
  const double sigma_q = 2e-3, sigma_tau = 0.5;
  const FourierTrajectory f = three_axis_excitation(period);
  const Trajectory exact = sample(f, dt, periods * period);
  Trajectory noisy = exact;
  noisy.source = "run1.csv";
  noisy.has_velocity = false;
  noisy.tau = torque_of(exact);
  std::mt19937_64 engine(20240611);
  add_noise(noisy.q, sigma_q, engine);
  add_noise(noisy.tau, sigma_tau, engine);

  const PeriodicAverage avg = average_periods(noisy, period);
  ASSERT_EQ(avg.periods, periods);
  ASSERT_EQ(avg.samples_per_period, 1000);
  EXPECT_EQ(avg.dropped_samples, 0);
  EXPECT_EQ(avg.averaged.source, "run1.csv");
  EXPECT_NEAR(avg.period, period, 1e-12);
  const Eigen::Index n = avg.samples_per_period;
  const Eigen::MatrixXd q_true = exact.q.topRows(n), tau_true = torque_of(exact).topRows(n);
  for (int j = 0; j < 3; ++j) {
    // The average of K samples has noise sigma / sqrt(K); the rms over 1000 samples estimates
    // it to about 2% (1 / sqrt(2 N)), so 10% is a 4.5-sigma bound.
    const double q_expected = sigma_q / std::sqrt(periods);
    const double tau_expected = sigma_tau / std::sqrt(periods);
    EXPECT_NEAR(rms(avg.averaged.q.col(j) - q_true.col(j)) / q_expected, 1.0, 0.1) << j;
    EXPECT_NEAR(rms(avg.averaged.tau.col(j) - tau_true.col(j)) / tau_expected, 1.0, 0.1) << j;
    // N (P - 1) = 9000 degrees of freedom: relative standard deviation sqrt(2 / 9000) = 1.5%;
    // 6% is 4 sigma, and tight enough to reject the (P - 1) / P = 0.9 bias of dividing by
    // P (P N - 1).
    EXPECT_NEAR(avg.q_noise_variance[j] / (q_expected * q_expected), 1.0, 0.06) << j;
    EXPECT_NEAR(avg.tau_noise_variance[j] / (tau_expected * tau_expected), 1.0, 0.06) << j;
  }
}

TEST(AveragePeriods, NoiseFreeRecordAveragesToOnePeriodExactly) {
  const FourierTrajectory f = three_axis_excitation(1.5);
  Trajectory x = sample(f, 0.005, 4 * 1.5);  // 300 per period
  x.tau = torque_of(x);
  const PeriodicAverage avg = average_periods(x, 1.5);
  ASSERT_EQ(avg.averaged.q.rows(), 300);
  EXPECT_LT((avg.averaged.q - x.q.topRows(300)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((avg.averaged.ddq - x.ddq.topRows(300)).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_LT(avg.q_noise_variance.maxCoeff(), 1e-26);
  EXPECT_EQ(avg.averaged.t, x.t.head(300));
}

TEST(AveragePeriods, ReportsTheDroppedHalfPeriod) {
  const double period = 2.0, dt = 0.01;
  Trajectory x = sample(three_axis_excitation(period), dt, 2.5 * period);  // 500 samples
  const PeriodicAverage avg = average_periods(x, period);
  EXPECT_EQ(avg.periods, 2);
  EXPECT_EQ(avg.samples_per_period, 200);
  EXPECT_EQ(avg.dropped_samples, 100);
  EXPECT_NEAR(avg.dropped_seconds, 0.5 * period, 1e-12);
}

TEST(AveragePeriods, RejectsBadRecordsWithTheFileName) {
  const double period = 2.0, dt = 0.01;
  Trajectory x = sample(three_axis_excitation(period), dt, 4 * period);
  x.source = "data/run7.csv";

  Trajectory jitter = x;
  jitter.t[123] += 0.3 * dt;
  expect_data_error([&] { average_periods(jitter, period); }, x.source, "not uniform");
  expect_data_error([&] { average_periods(jitter, period); }, x.source, "sample 124");
  // 200.5 samples per period: misaligned by 2 samples after 4 periods.
  expect_data_error([&] { average_periods(x, 200.5 * dt); }, x.source,
                    "not a whole number of samples");
  Trajectory short_record = sample(three_axis_excitation(period), dt, 1.5 * period);
  short_record.source = x.source;
  expect_data_error([&] { average_periods(short_record, period); }, x.source,
                    "at least 2 whole periods");
  expect_data_error([&] { average_periods(x, 0.0); }, x.source, "positive");
  Trajectory nan = x;
  nan.tau(17, 1) = std::nan("");
  expect_data_error([&] { average_periods(nan, period); }, x.source, "column 'tau2'");
}

TEST(DetectPeriod, FindsTheCommonPeriodOfMultiSinesWithAWeakFundamental) {
  // Axis 1 is mostly its third harmonic, axis 2 its second and fifth: the dominant lines
  // suggest T/3 and T/2, only T brings both back into phase.
  FourierTrajectory f;
  f.period = 2.0;
  f.q0 = Eigen::Vector2d(0.1, 0.2);
  f.a = (Eigen::MatrixXd(2, 5) << 0.05, 0, 1.0, 0, 0, 0, 0.8, 0, 0, 0.6).finished();
  f.b = (Eigen::MatrixXd(2, 5) << 0.02, 0, 0.3, 0, 0, 0, 0.1, 0, 0, -0.4).finished();
  const double dt = 0.002;
  for (const double period : {2.0, 2.0 + 0.37 * dt}) {  // on and off the sample grid
    f.period = period;
    Trajectory x = sample(f, dt, 4.3 * period);
    std::mt19937_64 engine(5);
    add_noise(x.q, 1e-3, engine);
    EXPECT_NEAR(detect_period(x), period, 0.02 * dt) << period;
  }
  // Dense sampling (5 kHz, 20000 samples per period, 6 periods): the peaks are flat over
  // many lags, yet the period is found closely enough to average the record with it directly.
  const FourierTrajectory slow = three_axis_excitation(4.0);
  Trajectory dense = sample(slow, 0.0002, 6 * slow.period);
  std::mt19937_64 engine(6);
  add_noise(dense.q, 1e-4, engine);
  const double period = detect_period(dense);
  EXPECT_NEAR(period, slow.period, 0.01 * 0.0002);
  const PeriodicAverage avg = average_periods(dense, period);
  EXPECT_EQ(avg.samples_per_period, 20000);
  EXPECT_EQ(avg.periods, 6);
}

TEST(DetectPeriod, NoPeriodOrTooFewPeriodsAreErrors) {
  Trajectory noise = sample(three_axis_excitation(2.0), 0.01, 10.0);
  noise.source = "noise.csv";
  noise.q.setZero();
  std::mt19937_64 engine(9);
  add_noise(noise.q, 1.0, engine);
  expect_data_error([&] { detect_period(noise); }, "noise.csv", "no period found");

  Trajectory still = noise;
  still.q.setConstant(0.4);
  expect_data_error([&] { detect_period(still); }, "noise.csv", "do not move");

  Trajectory ramp = noise;
  for (Eigen::Index s = 0; s < ramp.q.rows(); ++s) ramp.q.row(s).setConstant(0.01 * s);
  expect_data_error([&] { detect_period(ramp); }, "noise.csv", "never decorrelate");

  Trajectory short_record = sample(three_axis_excitation(2.0), 0.01, 1.6 * 2.0);
  short_record.source = "short.csv";
  expect_data_error([&] { detect_period(short_record); }, "short.csv", "at least 2 periods");
}

// Real data (../shared/datasets, see SOURCES.md there)

std::vector<double> read_numbers(const std::string& path) {
  std::ifstream in(path);
  std::vector<double> values;
  double v = 0;
  while (in >> v) values.push_back(v);
  return values;
}

TEST(RealData, PandaExcitationRepeatsButHoldsFewerThanTwoPeriods) {
  const std::string dir = test::shared_path("datasets/panda-gaz2019/");
  const std::vector<double> time = read_numbers(dir + "exciting_traj_time.txt");
  const std::vector<double> positions = read_numbers(dir + "exciting_traj_positions.txt");
  if (time.empty()) GTEST_SKIP() << "no Panda data set in " << dir;
  ASSERT_EQ(positions.size(), 7 * time.size());
  // The log's time steps jitter (0.7 to 8.8 ms): resample linearly on a 1 ms grid.
  const double dt = 1e-3;
  const auto n = static_cast<Eigen::Index>(time.back() / dt) + 1;
  Trajectory x;
  x.source = "panda";
  x.t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) * dt);
  x.q.resize(n, 7);
  x.tau = Eigen::MatrixXd::Zero(n, 7);
  std::size_t k = 0;
  for (Eigen::Index s = 0; s < n; ++s) {
    while (k + 2 < time.size() && time[k + 1] < x.t[s]) ++k;
    const double a = std::clamp((x.t[s] - time[k]) / (time[k + 1] - time[k]), 0.0, 1.0);
    for (int j = 0; j < 7; ++j) {
      x.q(s, j) = (1 - a) * positions[7 * k + j] + a * positions[7 * (k + 1) + j];
    }
  }
  double period = 0;
  try {
    detect_period(x);
    ADD_FAILURE() << "21 s of a 13 s periodic motion accepted";
  } catch (const DataError& e) {
    const std::string what = e.what();
    const std::size_t at = what.find("period of ");
    ASSERT_NE(at, std::string::npos) << what;
    period = std::stod(what.substr(at + 10));
    EXPECT_NE(what.find("(1.57"), std::string::npos) << what;
  }
  // Independently: q(t + T) repeats q(t) to a few percent of the motion at the period found,
  // and not half a second away from it.
  auto mismatch = [&](double lag) {
    const auto m = static_cast<Eigen::Index>(std::llround(lag / dt));
    const Eigen::Index from = 1000;  // after the start from rest
    const Eigen::MatrixXd a = x.q.middleRows(from, n - m - from);
    const Eigen::MatrixXd b = x.q.middleRows(from + m, n - m - from);
    const Eigen::RowVectorXd mean = a.colwise().mean();
    return (b - a).norm() / (a.rowwise() - mean).norm();
  };
  EXPECT_GT(period, 13.0);
  EXPECT_LT(period, 13.7);
  EXPECT_LT(mismatch(period), 0.05);
  EXPECT_GT(mismatch(period - 0.5), 0.2);
  EXPECT_GT(mismatch(period + 0.5), 0.2);
}

}  // namespace
}  // namespace modelgen
