// The filter plan and the excitation bandwidth (modelgen/signal/filter_plan.hpp): the
// documented rule, and the highest excited frequency despite sensor noise, quantization and
// coloured noise.

#include <algorithm>
#include <cmath>
#include <complex>
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
#include "modelgen/signal/filter_plan.hpp"
#include "modelgen/signal/lowpass.hpp"

#include "tests/runtime/signal/signal_test_support.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using namespace signal_test;  // tests/runtime/signal/signal_test_support.hpp

TEST(PlanFiltering, FollowsTheDocumentedRule) {
  const FilterPlan plan = plan_filtering(5000, 5);
  EXPECT_DOUBLE_EQ(plan.position_cutoff_hz, 50);
  EXPECT_EQ(plan.decimation_factor, 200);  // 0.8 * 2500 / 200 = 10 Hz = 2 x 5 Hz
  EXPECT_DOUBLE_EQ(plan.decimation_cutoff_hz, 10);
  EXPECT_NE(plan.explanation.find("decimated by 200"), std::string::npos) << plan.explanation;
  EXPECT_NE(plan.explanation.find("keeps 2 x the bandwidth"), std::string::npos)
      << plan.explanation;
  // The kept band lies 5 times below the position filter's cut-off, where the filter run
  // twice (|H|^2 of a 4th-order Butterworth) passes 99.99 %: W and Y share the band.
  EXPECT_GT(std::norm(butterworth_lowpass(4, 50, 5000).response(10)), 0.9999);

  const FilterPlan fast = plan_filtering(5000, 300);  // 10 x 300 > 0.8 x 2500
  EXPECT_DOUBLE_EQ(fast.position_cutoff_hz, 2000);
  EXPECT_EQ(fast.decimation_factor, 3);  // 2000 / 3 = 667 Hz >= 2 x 300 Hz > 2000 / 4
  EXPECT_NE(fast.explanation.find("0.8 x Nyquist"), std::string::npos) << fast.explanation;

  EXPECT_EQ(plan_filtering(1000, 300).decimation_factor, 1);
  // The rule's 71 (400 / 71 = 5.63 Hz >= 2 x 2.8 Hz) has a prime above 10: 70 = 10 x 7 runs in
  // stages, and the explanation shows them.
  const FilterPlan staged = plan_filtering(1000, 2.8);
  EXPECT_EQ(staged.decimation_factor, 70);
  EXPECT_NE(staged.explanation.find("stages 10 x 7"), std::string::npos) << staged.explanation;
  EXPECT_THROW(plan_filtering(1000, 600), std::invalid_argument);
  EXPECT_THROW(plan_filtering(0, 1), std::invalid_argument);
}

TEST(PlanFiltering, LeavesTwentyRowsPerParameter) {
  // 30 s at 1 kHz of a 0.1 Hz excitation: the band alone would allow 400 / 0.2 = 2000, which
  // leaves 15 rows x 6 axes for 61 parameters. At most 30000 x 6 / (20 x 61) = 147.5: 147
  // (3 x 7 x 7) leaves 204 rows per axis, 20.07 per parameter.
  const FilterPlan plan = plan_filtering(1000, 0.1, {30000, 6, 61});
  EXPECT_EQ(plan.decimation_factor, 147);
  EXPECT_GE(30000.0 / plan.decimation_factor * 6 / 61, 20.0);
  EXPECT_LT(30000.0 / 150 * 6 / 61, 20.0);  // the next stageable factor would not
  EXPECT_NE(plan.explanation.find("rows per parameter"), std::string::npos) << plan.explanation;
  // A budget the band's bound already meets changes nothing.
  EXPECT_EQ(plan_filtering(1000, 2.8, {30000, 6, 61}).decimation_factor, 70);
  EXPECT_EQ(plan_filtering(1000, 0.1, {30000, 6, 0}).decimation_factor,
            plan_filtering(1000, 0.1).decimation_factor);
}

TEST(EstimateBandwidth, FindsTheHighestExcitedFrequency) {
  // Velocity lines of equal amplitude at 1, 2 and 3 Hz: 99% of the energy lies below 3 Hz plus
  // the Hann window's main lobe (2 / 20 s = 0.1 Hz).
  const double fs = 1000;
  const Eigen::Index n = 20000;
  Trajectory x;
  x.t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  x.q = Eigen::MatrixXd::Zero(n, 2);
  x.tau = x.q;
  for (const double f : {1.0, 2.0, 3.0}) {
    x.q.col(0) += ((2 * kPi * f * x.t).array().sin() / (2 * kPi * f)).matrix();
  }
  x.q.col(1) = 0.3 * ((2 * kPi * 1.5 * x.t).array().cos()).matrix();
  const double bandwidth = estimate_bandwidth(x);
  EXPECT_GT(bandwidth, 2.9);
  EXPECT_LT(bandwidth, 3.1);
}

TEST(EstimateBandwidth, IgnoresSensorNoiseAndQuantization) {
  // The same motion with sensor noise (0.5e-3 rad) read by an encoder with 1e-3 rad steps:
  // differentiated, noise and steps would hold most of the velocity energy, at high
  // frequencies; the noise floor is subtracted.
  const double fs = 1000;
  const Eigen::Index n = 20000;
  Trajectory x;
  x.source = "quantized.csv";
  x.t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  x.q = Eigen::MatrixXd::Zero(n, 1);
  x.tau = x.q;
  for (const double f : {1.0, 2.0, 3.0}) {
    x.q.col(0) += ((2 * kPi * f * x.t).array().sin() / (2 * kPi * f)).matrix();
  }
  std::mt19937_64 engine(21);
  add_noise(x.q, 0.5e-3, engine);
  x.q = (x.q.array() / 1e-3).round() * 1e-3;
  const double bandwidth = estimate_bandwidth(x);
  EXPECT_GT(bandwidth, 2.9);
  EXPECT_LT(bandwidth, 3.1);

  x.q.setConstant(0.25);
  expect_data_error([&] { estimate_bandwidth(x); }, "quantized.csv", "do not move");
}

// A slow five-harmonic excitation as the Panda run's (period 13.35 s, top harmonic 0.375 Hz),
// sampled at 1 kHz for 20 s.
Trajectory slow_excitation(Eigen::Index axes) {
  const double fs = 1000, period = 13.35;
  const Eigen::Index n = 20000;
  Trajectory x;
  x.source = "slow.csv";
  x.t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  x.q = Eigen::MatrixXd::Zero(n, axes);
  x.tau = x.q;
  for (Eigen::Index j = 0; j < axes; ++j) {
    for (int l = 1; l <= 5; ++l) {
      const double w = 2 * kPi * l / period;
      x.q.col(j) += (0.3 / l * ((w * x.t).array() + 0.7 * (j + l)).sin()).matrix();
    }
  }
  return x;
}

TEST(EstimateBandwidth, IgnoresColouredNoise) {
  // Noise that falls with frequency (white noise through a 100 Hz low-pass, as timing jitter or
  // interpolated, held positions give): a noise floor taken from the top of the band sees only
  // its tail, and the velocity weighting (2 pi f)^2 then makes the noise between 1 and 100 Hz
  // the "bandwidth" (the Panda run gave 80.4 Hz). The motion ends at 0.375 Hz, plus the Hann
  // main lobe (2 / 32.8 s).
  Trajectory x = slow_excitation(3);
  std::mt19937_64 engine(17);
  Eigen::MatrixXd noise = Eigen::MatrixXd::Zero(x.q.rows(), x.q.cols());
  add_noise(noise, 2e-3, engine);
  filter_causal(butterworth_lowpass(2, 100, 1000), noise);
  x.q += noise;
  const double bandwidth = estimate_bandwidth(x);
  EXPECT_GT(bandwidth, 0.35);
  EXPECT_LT(bandwidth, 0.5);
}

TEST(EstimateBandwidth, KeepsTheTorquesBandWhenItIsWider) {
  // Torques reach above the motion (here sin(5 q), as the dynamics' sines of q give):
  // the decimation must keep both sides of tau = W beta, so the bandwidth is the torques'.
  Trajectory x = slow_excitation(1);
  x.tau.col(0) = (4.0 * (5.0 * x.q.col(0).array()).sin()).matrix();
  const ExcitationBands bands = estimate_bands(x);
  EXPECT_LT(bands.velocity_hz, 0.5);
  EXPECT_GT(bands.torque_hz, bands.velocity_hz);
  EXPECT_EQ(bands.bandwidth_hz, bands.torque_hz);
  // Without measured torques (predict on positions only), the motion's band alone.
  x.measured = Measured::kNothing;
  EXPECT_EQ(estimate_bands(x).torque_hz, 0);
  EXPECT_EQ(estimate_bandwidth(x), estimate_bands(x).velocity_hz);
}

}  // namespace
}  // namespace modelgen
