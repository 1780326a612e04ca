// The checks of a preparation against its data: the encoder noise read from the positions'
// spectrum against the noise that made them, the acceleration noise it predicts against the
// rms of the noise alone run through the preparation (filter, second differences,
// decimation), and the warnings the checks give, naming the option to change.

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/signal/decimation.hpp"
#include "modelgen/signal/differentiation.hpp"
#include "modelgen/signal/preparation_checks.hpp"

namespace modelgen {
namespace {

constexpr double kRate = 1000;

// 30 s at 1 kHz of slow sines (0.1 to 0.5 Hz, 1 rad) on two axes plus white noise `sigma`.
Trajectory noisy_motion(double sigma, unsigned seed) {
  const Eigen::Index n = 30000;
  Trajectory x;
  x.t = Eigen::VectorXd::LinSpaced(n, 0, (n - 1) / kRate);
  x.q.resize(n, 2);
  x.tau = Eigen::MatrixXd::Zero(n, 2);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, sigma);
  for (Eigen::Index s = 0; s < n; ++s) {
    for (int j = 0; j < 2; ++j) {
      double q = 0;
      for (int h = 1; h <= 5; ++h) q += 0.2 * std::sin(2 * std::numbers::pi * 0.1 * h * x.t[s] + j);
      x.q(s, j) = q + (sigma > 0 ? noise(rng) : 0);
    }
  }
  return x;
}

TEST(PositionNoise, ReadsWhiteNoiseAboveTheMotion) {
  const Eigen::VectorXd sigma = position_noise_std(noisy_motion(1e-4, 1));
  for (Eigen::Index j = 0; j < 2; ++j) EXPECT_NEAR(sigma[j], 1e-4, 5e-6);
}

TEST(AccelerationNoise, MatchesTheNoiseRunThroughThePreparation) {
  // White noise alone through the position filter, second differences and a decimation:
  // the rms left against the formula, for a narrow and a wide kept band.
  Trajectory x = noisy_motion(1e-4, 2);
  x.q -= noisy_motion(0, 2).q;
  for (const auto& [cutoff, factor] : std::vector<std::pair<double, int>>{{7, 100}, {100, 10}}) {
    Trajectory y = x;
    filter_positions(y, cutoff, 4);
    const Eigen::Index edge = 2000;  // clear of the filter's and the decimation's ends
    const Eigen::MatrixXd ddq =
        decimate(y.ddq, factor).middleRows(edge / factor, (y.ddq.rows() - 2 * edge) / factor);
    const double rms = std::sqrt(ddq.array().square().mean());
    const double kept = 0.4 * kRate / factor;
    EXPECT_NEAR(acceleration_noise_std(1e-4, cutoff, kept, kRate) / rms, 1.0, 0.1)
        << "cutoff " << cutoff << " decimation " << factor;
  }
}

PreparationFacts facts_for(double q_noise, double cutoff, int decimation) {
  Trajectory x = noisy_motion(0, 3);
  differentiate(x);
  PreparationFacts f;
  f.source = "run.csv";
  f.sample_rate_hz = kRate;
  f.bandwidth_hz = 0.5;
  f.cutoff_hz = cutoff;
  f.decimation = decimation;
  f.cutoff_given = f.decimation_given = true;
  f.planned_cutoff_hz = 5;
  f.planned_decimation = 200;
  f.samples = x.t.size();
  f.unknowns = 10;
  f.q_noise_std = Eigen::VectorXd::Constant(2, q_noise);
  f.ddq = x.ddq;
  // Torques of the motion plus white noise over the whole band: most of their power lies
  // above twice the excitation band, as under a D term acting on encoder noise.
  std::mt19937 rng(4);
  std::normal_distribution<double> noise(0, 1);
  f.tau = x.ddq;
  for (Eigen::Index s = 0; s < f.tau.rows(); ++s) {
    for (Eigen::Index j = 0; j < f.tau.cols(); ++j) f.tau(s, j) += 10 * noise(rng);
  }
  return f;
}

TEST(CheckPreparation, NamesTheOptionThatBreaksTheFit) {
  // The motion's accelerations: 0.2 (2 pi 0.1 h)^2 summed over h = 1..5, some 3 rad/s^2 rms.
  EXPECT_TRUE(check_preparation(facts_for(1e-6, 5, 200)).empty());
  // 1e-4 rad of noise kept up to 40 Hz: about 0.8 rad/s^2 of noise, the inertia terms shrink.
  const std::vector<std::string> wide = check_preparation(facts_for(1e-4, 100, 10));
  ASSERT_EQ(wide.size(), 2u);
  EXPECT_NE(wide[0].find("run.csv: warning: errors in the variables"), std::string::npos)
      << wide[0];
  EXPECT_NE(wide[0].find("lower --cutoff or raise --decimate"), std::string::npos) << wide[0];
  EXPECT_NE(wide[1].find("keeps up to 40 Hz, 80 times the excitation's"), std::string::npos)
      << wide[1];
  // The same kept band with clean torques: no warning about it.
  PreparationFacts clean = facts_for(1e-6, 100, 10);
  clean.tau = clean.ddq;
  EXPECT_TRUE(check_preparation(clean).empty());
  // 30000 samples x 2 axes / 10000 = 6 rows for 10 parameters.
  const std::vector<std::string> few = check_preparation(facts_for(1e-6, 5, 10000));
  ASSERT_EQ(few.size(), 1u);
  EXPECT_NE(few[0].find("fewer than 20 per parameter"), std::string::npos) << few[0];
  EXPECT_NE(few[0].find("lower --decimate"), std::string::npos) << few[0];
}

}  // namespace
}  // namespace modelgen
