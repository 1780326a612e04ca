// reversal_min_speed (issue 31): the minimum speed chosen from a record, against a noisy encoder
// with a known sigma and a known filter (the wrong-sign fraction above and below it, counted
// against the true velocity written here) and the filter's noise gain against its closed form.

#include "modelgen/signal/reversal_speed.hpp"

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/signal/differentiation.hpp"

namespace modelgen {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRate = 1000.0, kCutoff = 20.0;
constexpr int kOrder = 4;

// (1/fs) int_-fs/2^fs/2 |H|^4 (fs sin(2 pi f / fs))^2 df: white noise of unit variance through
// the filter run twice (|H|^2 = 1 / (1 + (tan(pi f/fs) / tan(pi fc/fs))^2N), each pass) and the
// central difference, whose response is i fs sin(2 pi f / fs). Midpoint rule.
double closed_form_gain(double cutoff, int order, double rate) {
  const int steps = 200000;
  double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const double f = (i + 0.5) / steps * rate / 2;  // one side, doubled below
    const double w = std::tan(kPi * f / rate) / std::tan(kPi * cutoff / rate);
    const double h2 = 1.0 / (1.0 + std::pow(w, 2 * order));
    const double d = rate * std::sin(2 * kPi * f / rate);
    sum += h2 * h2 * d * d;
  }
  return std::sqrt(2.0 * sum * (rate / 2 / steps) / rate);
}

TEST(ReversalSpeed, NoiseGainIsTheFiltersClosedForm) {
  for (const double cutoff : {5.0, 20.0, 100.0}) {
    EXPECT_NEAR(velocity_noise_gain(cutoff, kOrder, kRate), closed_form_gain(cutoff, kOrder, kRate),
                1e-4 * closed_form_gain(cutoff, kOrder, kRate))
        << cutoff;
  }
}

// A joint swinging q = A sin(2 pi f0 t) at 1 kHz; with `dwell` > 0 it stops for `dwell` seconds
// at each turning point (the true velocity 0 there, the motion resumed as the sine's). Returns
// the record with encoder noise of std `sigma` and fills the true velocity.
Trajectory swing(double sigma, double dwell, Eigen::VectorXd& true_dq, unsigned seed) {
  const double amplitude = 1.0, f0 = 0.5, seconds = 20.0;
  const Eigen::Index m = static_cast<Eigen::Index>(seconds * kRate);
  Trajectory x;
  x.source = "swing";
  x.t = Eigen::VectorXd::LinSpaced(m, 0, static_cast<double>(m - 1) / kRate);
  x.q.resize(m, 1);
  x.tau = Eigen::MatrixXd::Zero(m, 1);
  true_dq.resize(m);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  const double half = 0.5 / f0;  // half a period of the sine, between turning points
  for (Eigen::Index s = 0; s < m; ++s) {
    // Time in the sine's own clock: each half period followed by a dwell.
    const double t = x.t[s], cycle = half + dwell;
    const double k = std::floor(t / cycle), r = t - k * cycle;
    const double phase = -0.25 / f0 + k * half + std::min(r, half);  // start at a turning point
    x.q(s, 0) = amplitude * std::sin(2 * kPi * f0 * phase) + noise(rng);
    true_dq[s] = r < half ? amplitude * 2 * kPi * f0 * std::cos(2 * kPi * f0 * phase) : 0.0;
  }
  return x;
}

struct SignCount {
  int above = 0, above_wrong = 0, below = 0, below_wrong = 0;
  int resting_above = 0, resting = 0;  // samples of a dwell: above the speed, all
};

// The prepared velocity's sign against the true one, above and below `speed`, where the true
// velocity is not 0 (the samples of a dwell have no sign) and away from the filter's edges.
SignCount count_signs(const Trajectory& raw, const Eigen::VectorXd& true_dq, double speed) {
  Trajectory x = raw;
  filter_positions(x, kCutoff, kOrder);
  SignCount c;
  const Eigen::Index edge = 500;
  for (Eigen::Index s = edge; s + edge < x.dq.rows(); ++s) {
    const double v = x.dq(s, 0), truth = true_dq[s + 1];  // differentiate drops the first sample
    if (std::abs(truth) < 1e-9) {  // at rest (a dwell, or a turning point's sample)
      ++c.resting;
      c.resting_above += std::abs(v) >= speed;
      continue;
    }
    const bool wrong = v * truth < 0;
    if (std::abs(v) >= speed) {
      ++c.above;
      c.above_wrong += wrong;
    } else {
      ++c.below;
      c.below_wrong += wrong;
    }
  }
  return c;
}

TEST(ReversalSpeed, NoisyEncoderSignUnreliableBelowTheChosenSpeedOnly) {
  // Clean reversals, encoder noise 2e-3 rad: the velocity noise decides.
  const double sigma = 2e-3;
  Eigen::VectorXd true_dq;
  const Trajectory raw = swing(sigma, 0.0, true_dq, 1);
  const ReversalSpeed chosen =
      reversal_min_speed(raw, kCutoff, kOrder, Eigen::VectorXd::Constant(1, sigma), 500);
  ASSERT_EQ(chosen.speed.size(), 1);
  EXPECT_NEAR(chosen.noise[0], 3 * sigma * closed_form_gain(kCutoff, kOrder, kRate),
              1e-3 * chosen.noise[0]);
  EXPECT_GT(chosen.noise[0], chosen.step[0]);  // the noise blurs each reversal over samples
  EXPECT_EQ(chosen.speed[0], std::max(chosen.noise[0], chosen.lag[0]));
  const SignCount c = count_signs(raw, true_dq, chosen.speed[0]);
  std::printf("noise %g lag %g: above %d (%d wrong), below %d (%d wrong), resting %d (%d above)\n",
              chosen.noise[0], chosen.lag[0], c.above, c.above_wrong, c.below, c.below_wrong,
              c.resting, c.resting_above);
  ASSERT_GT(c.below, 100);
  EXPECT_LT(c.above_wrong, 0.002 * c.above) << c.above_wrong << " of " << c.above;
  EXPECT_GT(c.below_wrong, 0.1 * c.below) << c.below_wrong << " of " << c.below;
  // A third of the speed leaves wrong signs above it.
  EXPECT_GT(count_signs(raw, true_dq, chosen.speed[0] / 3).above_wrong, c.above_wrong);
}

TEST(ReversalSpeed, CleanReversalsAndAQuietEncoderLeaveNothingBelow) {
  // Smooth reversals, encoder noise 1e-7 rad: the zero-phase filter keeps the velocity's sign,
  // the chosen speed lies below the velocity's step per sample (no sample is slower).
  const double sigma = 1e-7;
  Eigen::VectorXd true_dq;
  const Trajectory raw = swing(sigma, 0.0, true_dq, 2);
  const ReversalSpeed chosen =
      reversal_min_speed(raw, kCutoff, kOrder, Eigen::VectorXd::Constant(1, sigma), 500);
  EXPECT_EQ(chosen.lag[0], 0.0);
  // The noise flips no sample at a reversal (3 sigma_v far below |ddq| dt there): nothing is
  // weighted, rather than two cut-off periods around a sample that happens to land near 0.
  const double step = 2 * kPi * 0.5 * 2 * kPi * 0.5 / kRate;  // |ddq| dt at the turning points
  EXPECT_NEAR(chosen.step[0], step, 0.01 * step);
  EXPECT_LT(chosen.noise[0], 0.01 * step);
  EXPECT_EQ(chosen.speed[0], 0.0);
  const SignCount c = count_signs(raw, true_dq, chosen.speed[0]);
  std::printf("noise %g lag %g: above %d (%d wrong), below %d (%d wrong), resting %d (%d above)\n",
              chosen.noise[0], chosen.lag[0], c.above, c.above_wrong, c.below, c.below_wrong,
              c.resting, c.resting_above);
  EXPECT_EQ(c.below, 0);
}

TEST(ReversalSpeed, ADwellAtEachReversalIsCoveredByTheLagTerm) {
  // The joint sticks 0.2 s at each turning point, where a Coulomb term's sign is undefined; the
  // filter's response to the stop and the start leaves small velocities of either sign there,
  // which the reference (4x the band) contradicts: the lag term covers them, so that the weight
  // is 0 over nearly the whole dwell, and no moving sample above it has a wrong sign.
  const double sigma = 1e-7;
  Eigen::VectorXd true_dq;
  const Trajectory raw = swing(sigma, 0.2, true_dq, 3);
  const ReversalSpeed chosen =
      reversal_min_speed(raw, kCutoff, kOrder, Eigen::VectorXd::Constant(1, sigma), 500);
  EXPECT_GT(chosen.lag[0], 100 * chosen.noise[0]);
  const SignCount c = count_signs(raw, true_dq, chosen.speed[0]);
  std::printf("noise %g lag %g: above %d (%d wrong), below %d (%d wrong), resting %d (%d above)\n",
              chosen.noise[0], chosen.lag[0], c.above, c.above_wrong, c.below, c.below_wrong,
              c.resting, c.resting_above);
  EXPECT_EQ(c.above_wrong, 0);
  ASSERT_GT(c.resting, 3000);
  EXPECT_LT(c.resting_above, 0.05 * c.resting);
  // The noise alone would leave most of the dwell in.
  const SignCount noise_only = count_signs(raw, true_dq, chosen.noise[0]);
  EXPECT_GT(noise_only.resting_above, 0.5 * noise_only.resting);
}

}  // namespace
}  // namespace modelgen
