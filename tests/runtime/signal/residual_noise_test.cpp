// The residual-against-noise check (modelgen/signal/residual_noise.hpp) on errors made here:
// white noise alone (what a right model leaves) stays within the bounds on every joint, a
// sinusoid in the band on one joint (what a model that misses something leaves) goes above on
// that joint only. The chi-square points are compared with tabulated values.

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "modelgen/signal/residual_noise.hpp"

namespace modelgen {
namespace {

constexpr double kDt = 0.01, kPeriod = 10.0;
constexpr int kPeriods = 3, kJoints = 3;

// One record of kPeriods periods: a periodic torque in the band, white noise of `sigma` as the
// error, plus `extra` times a 0.3 Hz sinusoid (in the 1 Hz band, repeating every period) on
// joint `joint`.
ResidualRecord record(unsigned seed, double sigma, int joint, double extra) {
  const int n = static_cast<int>(kPeriods * kPeriod / kDt);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  ResidualRecord r;
  r.dt = kDt;
  r.band.band_hz = 1.0;
  r.band.period = kPeriod;
  r.tau.resize(n, kJoints);
  r.error.resize(n, kJoints);
  for (int k = 0; k < n; ++k) {
    const double t = k * kDt;
    for (int j = 0; j < kJoints; ++j) {
      r.tau(k, j) = 10 * std::sin(2 * std::numbers::pi * 0.1 * t + j);
      r.error(k, j) = noise(rng);
      if (j == joint) r.error(k, j) += extra * std::sin(2 * std::numbers::pi * 0.3 * t);
    }
  }
  return r;
}

TEST(ChiSquarePoint, MatchesTables) {
  // chi-square 0.9995 and 0.0005 points: 10 dof 31.42 and 1.26 (0.0005: 1.2650), 100 dof 153.2
  // and 59.9 (from the regularised incomplete gamma function; Wilson-Hilferty is within 10 %
  // at 10 dof).
  EXPECT_NEAR(chi_square_point(kResidualCheckZ, 10), 31.42, 0.5);
  EXPECT_NEAR(chi_square_point(-kResidualCheckZ, 10), 1.265, 0.15);
  EXPECT_NEAR(chi_square_point(kResidualCheckZ, 100), 153.2, 0.5);
  EXPECT_NEAR(chi_square_point(-kResidualCheckZ, 100), 59.9, 0.5);
  EXPECT_EQ(chi_square_point(-kResidualCheckZ, 0.5), 0);
}

TEST(ResidualAgainstNoise, WhiteNoiseStaysWithinTheBounds) {
  // 60 joints of white noise: the ratios' mean near 1, their spread what the degrees of
  // freedom claim (sqrt(2 / nu_r + 2 / nu_n) for a ratio of two chi-squares over their dof,
  // to first order), and none outside the bounds (0.1 % false alarms each).
  int outside = 0;
  double sum = 0, sum_squares = 0, claimed = 0;
  const int count = 60;
  for (unsigned seed = 1; seed <= count / kJoints; ++seed) {
    const std::vector<JointResidual> joints = residual_against_noise({record(seed, 0.1, -1, 0.0)});
    ASSERT_EQ(joints.size(), 3u);
    for (const JointResidual& r : joints) {
      ASSERT_FALSE(std::isnan(r.ratio));
      EXPECT_LT(r.lower, 1.0);
      EXPECT_GT(r.upper, 1.0);
      if (r.ratio > r.upper || r.ratio < r.lower) ++outside;
      sum += r.ratio;
      sum_squares += r.ratio * r.ratio;
      claimed = std::sqrt(2 / r.residual_dof + 2 / r.noise_dof);
    }
  }
  EXPECT_EQ(outside, 0);
  const double mean = sum / count, spread = std::sqrt(sum_squares / count - mean * mean);
  // The mean of 60 ratios of spread ~0.4 is within 0.15 of 1 at 3 sd (the ratio of two
  // chi-squares is biased up by about 2 / nu_n, 0.1).
  EXPECT_NEAR(mean, 1.0, 0.25) << spread;
  // The dof may not claim a spread much smaller than the real one (that would give false
  // alarms) nor much larger (a check that never fires); 60 values give the spread to 10 %.
  EXPECT_GT(spread, 0.6 * claimed) << mean;
  EXPECT_LT(spread, 1.4 * claimed) << mean;
}

TEST(ResidualAgainstNoise, AMissedSinusoidIsAboveOnItsJointOnly) {
  // 0.5 amplitude: 0.125 of energy per sample against the noise's 0.01 in the whole band,
  // of which the band keeps 2 x 1 Hz / 100 Hz: 0.0002 per sample; the ratio is some 600.
  const std::vector<JointResidual> joints = residual_against_noise({record(7, 0.1, 1, 0.5)});
  EXPECT_LE(joints[0].ratio, joints[0].upper);
  EXPECT_GT(joints[1].ratio, joints[1].upper);
  EXPECT_GT(joints[1].ratio, 100);
  EXPECT_LE(joints[2].ratio, joints[2].upper);
  EXPECT_EQ(joints[1].noise_origin.find("period to period") != std::string::npos, true);
}

TEST(ResidualAgainstNoise, NoRecordIsAnError) {
  EXPECT_THROW(residual_against_noise({}), std::invalid_argument);
  EXPECT_THROW(period_residual_against_noise({}), std::invalid_argument);
}

// Averaged periods (the periodic route): P periods of N samples of white noise `sigma` averaged
// here, the error the average plus `extra` times a sinusoid at `harmonic` on joint `joint`; the
// noise of the average from the periods' spread, computed here (per-sample variance over the
// periods, divided by P), or with `exact_lines` the lines' true variance N sigma^2 / P.
PeriodRecord period(unsigned seed, int joint, double extra, int harmonic, bool exact_lines) {
  constexpr int kN = 200, kP = 4, kBand = 10;
  constexpr double kSigma = 0.1;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, kSigma);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(kN, kJoints), squares = sum;
  for (int p = 0; p < kP; ++p) {
    for (int k = 0; k < kN; ++k) {
      for (int j = 0; j < kJoints; ++j) {
        const double x = noise(rng);
        sum(k, j) += x;
        squares(k, j) += x * x;
      }
    }
  }
  PeriodRecord r;
  r.error = sum / kP;
  r.tau = Eigen::MatrixXd::Constant(kN, kJoints, 5.0);
  const Eigen::MatrixXd deviations = squares - kP * r.error.cwiseAbs2();
  r.white = deviations.colwise().sum().transpose() / (kN * (kP - 1.0)) / kP;
  if (exact_lines)
    r.lines = Eigen::MatrixXd::Constant(kBand + 1, kJoints, kN * kSigma * kSigma / kP);
  for (int k = 0; k < kN; ++k) {
    r.error(k, joint) += extra * std::sin(2 * std::numbers::pi * harmonic * k / kN);
  }
  r.periods = kP;
  r.band = kBand;
  return r;
}

TEST(PeriodResidualAgainstNoise, NoiseStaysWithinTheBounds) {
  int outside = 0;
  double sum = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    for (const bool exact : {false, true}) {
      for (const JointResidual& r :
           period_residual_against_noise({period(seed, 0, 0.0, 3, exact)})) {
        ASSERT_FALSE(std::isnan(r.ratio));
        EXPECT_EQ(r.residual_dof, 21);
        EXPECT_EQ(r.noise_dof, 63);
        if (r.ratio > r.upper || r.ratio < r.lower) ++outside;
        sum += r.ratio;
      }
    }
  }
  EXPECT_EQ(outside, 0);
  // 60 residuals (each judged twice) of ratio spread ~0.36 (sqrt(2/21 + 2/63)): 0.05 a mean.
  EXPECT_NEAR(sum / 120, 1.0, 0.15);
}

TEST(PeriodResidualAgainstNoise, AMissedHarmonicInTheBandIsAboveOnItsJointOnly) {
  // Amplitude 0.1 at harmonic 3: energy 1 (0.01 / 2 per sample x 200) against the noise's 21
  // lines of 0.0025: 0.0525; a ratio near 20, the bound about 4.5.
  const std::vector<JointResidual> in_band =
      period_residual_against_noise({period(3, 2, 0.1, 3, false)});
  EXPECT_LE(in_band[0].ratio, in_band[0].upper);
  EXPECT_LE(in_band[1].ratio, in_band[1].upper);
  EXPECT_GT(in_band[2].ratio, in_band[2].upper);
  // The same above the band (harmonic 30 of a band of 10) is not the band's.
  const std::vector<JointResidual> above =
      period_residual_against_noise({period(3, 2, 0.1, 30, false)});
  EXPECT_LE(above[2].ratio, above[2].upper);
}

}  // namespace
}  // namespace modelgen
