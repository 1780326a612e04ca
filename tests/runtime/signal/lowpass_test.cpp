// Low-pass filters and zero-phase filtering (modelgen/signal/lowpass.hpp): Butterworth and
// Chebyshev responses against the analytic magnitudes with bilinear pre-warping, filtfilt on
// polynomials, and derivatives of filtered signals against analytic ones (Gautier & Briot IV.A).

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
#include "modelgen/signal/differentiation.hpp"
#include "modelgen/signal/lowpass.hpp"

#include "tests/runtime/signal/signal_test_support.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using namespace signal_test;  // tests/runtime/signal/signal_test_support.hpp

TEST(Butterworth, ResponseMatchesTheAnalyticMagnitude) {
  const double fs = 1000, fc = 50;
  for (int order = 1; order <= 9; ++order) {
    const LowPassFilter filter = butterworth_lowpass(order, fc, fs);
    EXPECT_NEAR(std::abs(filter.response(0.0)), 1.0, 1e-14);
    EXPECT_NEAR(20 * std::log10(std::abs(filter.response(fc))), -3.0103, 1e-4) << order;
    for (const double f : {5.0, 25.0, 49.0, 51.0, 80.0, 150.0, 300.0, 499.0}) {
      const double expected = butterworth_gain(f, fc, fs, order);
      EXPECT_NEAR(std::abs(filter.response(f)) / expected, 1.0, 1e-9) << order << " " << f;
    }
  }
}

TEST(Butterworth, FilteredSinesHaveTheExpectedGainOnceAndTwice) {
  const double fs = 1000, fc = 50;
  const int order = 4;
  const LowPassFilter filter = butterworth_lowpass(order, fc, fs);
  const Eigen::Index n = 20000;
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  for (const double f : {10.0, 50.0, 120.0}) {
    Eigen::MatrixXd x(n, 2);
    x.col(0) = (2 * kPi * f * t).array().sin();
    x.col(1) = x.col(0);
    filter_causal(filter, x.col(0));
    filtfilt(filter, x.col(1));
    // Steady state, far from both ends; a whole number of cycles of every frequency here.
    const Eigen::Index from = 5000, len = 10000;
    const SineFit once = fit_sine(t.segment(from, len), x.col(0).segment(from, len), f);
    const SineFit twice = fit_sine(t.segment(from, len), x.col(1).segment(from, len), f);
    const double gain = butterworth_gain(f, fc, fs, order);
    EXPECT_NEAR(once.amplitude / gain, 1.0, 1e-6) << f;
    EXPECT_NEAR(twice.amplitude / (gain * gain), 1.0, 1e-6) << f;
    EXPECT_NEAR(twice.phase, 0.0, 1e-6) << f;  // zero phase: not shifted
  }
  // -3 dB after one pass, -6 dB after filtfilt at the cut-off.
  EXPECT_NEAR(20 * std::log10(butterworth_gain(fc, fc, fs, order)), -3.0103, 1e-4);
}

TEST(Chebyshev, ResponseMatchesTheAnalyticMagnitude) {
  const double fs = 1.0, fc = 0.04, ripple = 0.05;
  const double eps2 = std::pow(10.0, ripple / 10) - 1;
  for (const int order : {3, 8}) {
    const LowPassFilter filter = chebyshev1_lowpass(order, ripple, fc, fs);
    // Unit DC gain: an even order is scaled up from its ripple minimum at DC.
    const double g = order % 2 == 0 ? 1 + eps2 : 1.0;
    for (const double f : {0.0, 0.01, 0.02, 0.035, 0.04, 0.05, 0.1, 0.3, 0.49}) {
      const double w = std::tan(kPi * f / fs) / std::tan(kPi * fc / fs);
      const double tn = chebyshev_polynomial(order, w);
      const double expected = std::sqrt(g / (1 + eps2 * tn * tn));
      EXPECT_NEAR(std::abs(filter.response(f)) / expected, 1.0, 1e-9) << order << " " << f;
    }
  }
}

TEST(Filtfilt, KeepsConstantsRampsAndLowOrderPolynomialsAwayFromTheEdges) {
  const double fs = 1000;
  const LowPassFilter filter = butterworth_lowpass(4, 20, fs);
  const Eigen::Index n = 4000;
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  Eigen::MatrixXd x(n, 3);
  x.col(0).setConstant(2.5);
  x.col(1) = 0.3 - 1.7 * t.array();
  x.col(2) = 0.2 + t.array() * (0.5 + t.array() * (-0.8 + 0.3 * t.array()));
  const Eigen::MatrixXd before = x;
  filtfilt(filter, x);
  EXPECT_LT((x.col(0) - before.col(0)).cwiseAbs().maxCoeff(), 1e-12);
  // Odd reflection continues a ramp exactly: no end effect at all.
  EXPECT_LT((x.col(1) - before.col(1)).cwiseAbs().maxCoeff(), 1e-9);
  // |H|^2 = 1 - O(w^8): polynomials below degree 8 pass unchanged inside the record; the
  // reflected curvature disturbs the ends only.
  EXPECT_LT((x.col(2) - before.col(2)).segment(500, n - 1000).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(FilterPositions, CentralDifferencesOfFilteredSignalsMatchTheAnalyticDerivatives) {
  const double fs = 1000, h = 1 / fs, f = 1.3, w = 2 * kPi * f;
  const Eigen::Index n = 5000;
  Trajectory x;
  x.source = "sine.csv";
  x.t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / fs);
  x.q.resize(n, 2);
  x.q.col(0) = 0.7 * (w * x.t.array()).sin() + 0.2;
  x.q.col(1) = 0.1 + x.t.array() * (0.4 + x.t.array() * (-0.3 + 0.05 * x.t.array()));
  x.tau = Eigen::MatrixXd::Zero(n, 2);
  auto errors = [&](const Trajectory& y) {
    const Eigen::ArrayXd t = y.t.array();
    const Eigen::Index from = 500, len = n - 2 - 1000;  // away from the edges
    const Eigen::ArrayXd dq0 = 0.7 * w * (w * t).cos(), ddq0 = -0.7 * w * w * (w * t).sin();
    const Eigen::ArrayXd dq1 = 0.4 + t * (-0.6 + 0.15 * t), ddq1 = -0.6 + 0.3 * t;
    return Eigen::Vector4d((y.dq.col(0).array() - dq0).segment(from, len).abs().maxCoeff(),
                           (y.ddq.col(0).array() - ddq0).segment(from, len).abs().maxCoeff(),
                           (y.dq.col(1).array() - dq1).segment(from, len).abs().maxCoeff(),
                           (y.ddq.col(1).array() - ddq1).segment(from, len).abs().maxCoeff());
  };
  // Noise-free: the filter passes 1.3 Hz (|H|^2 = 1 - 3e-10 at a 20 Hz cut-off) and cubics
  // unchanged; what remains is the central differences' h^2 q''' / 6 on dq and h^2 q'''' / 12
  // on ddq (zero for the cubic).
  Trajectory clean = x;
  filter_positions(clean, 20.0);
  ASSERT_EQ(clean.t.size(), n - 2);
  ASSERT_TRUE(clean.has_velocity);
  const Eigen::Vector4d e = errors(clean);
  EXPECT_LT(e[0], 1.2 * h * h * 0.7 * std::pow(w, 3) / 6);
  EXPECT_LT(e[1], 1.2 * h * h * 0.7 * std::pow(w, 4) / 12);
  EXPECT_LT(e[2], 1.2 * h * h * 0.3 / 6);
  EXPECT_LT(e[3], 1e-5);

  // Encoder-like noise of 1e-6 rad: low-passed at 20 Hz its derivatives have a standard
  // deviation of about sigma sqrt(2 fc / fs) (2 pi fc)^k / sqrt(2k + 1), k = 1, 2; 6 sigma.
  Trajectory noisy = x;
  std::mt19937_64 engine(3);
  add_noise(noisy.q, 1e-6, engine);
  filter_positions(noisy, 20.0);
  const double band = 1e-6 * std::sqrt(2 * 20 / fs), wc = 2 * kPi * 20;
  const Eigen::Vector4d en = errors(noisy);
  EXPECT_LT(en[0], e[0] + 6 * band * wc / std::sqrt(3.0));
  EXPECT_LT(en[1], e[1] + 6 * band * wc * wc / std::sqrt(5.0));
  EXPECT_LT(en[2], e[2] + 6 * band * wc / std::sqrt(3.0));
  EXPECT_LT(en[3], e[3] + 6 * band * wc * wc / std::sqrt(5.0));
  std::printf("derivative errors noise-free %.3g %.3g %.3g %.3g, noisy %.3g %.3g %.3g %.3g\n", e[0],
              e[1], e[2], e[3], en[0], en[1], en[2], en[3]);

  expect_data_error([&] { filter_positions(x, 600.0); }, "sine.csv", "Nyquist frequency 500 Hz");
}

}  // namespace
}  // namespace modelgen
