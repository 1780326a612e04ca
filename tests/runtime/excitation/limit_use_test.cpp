// The extremes and limit uses of a Fourier excitation against closed forms: one harmonic l of
// velocity amplitudes (a, b) has q - q0 = (a sin - b cos)(l wf t) / (l wf), whose amplitude is
// r / (l wf) with r = hypot(a, b); |dq| peaks at r and |ddq| at r l wf.

#include "modelgen/excitation/limit_use.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace modelgen {
namespace {

FourierTrajectory one_harmonic(double period, double q0, int l, double a, double b) {
  FourierTrajectory x;
  x.period = period;
  x.q0 = Eigen::VectorXd::Constant(1, q0);
  x.a = Eigen::MatrixXd::Zero(1, l);
  x.b = Eigen::MatrixXd::Zero(1, l);
  x.a(0, l - 1) = a;
  x.b(0, l - 1) = b;
  return x;
}

TEST(LimitUse, OneHarmonicPeaksAreTheClosedForm) {
  const double period = 7.3, q0 = 0.4, a = 0.9, b = -0.35;
  const int l = 3;
  const double w = l * 2 * std::numbers::pi / period, r = std::hypot(a, b);
  const std::vector<JointExtremes> e = trajectory_extremes(one_harmonic(period, q0, l, a, b));
  ASSERT_EQ(e.size(), 1u);
  // The grid misses a peak by at most (pi / 1000)^2 / 2 of it.
  const double tolerance = 5e-6;
  EXPECT_NEAR(e[0].q_max, q0 + r / w, tolerance * r / w);
  EXPECT_NEAR(e[0].q_min, q0 - r / w, tolerance * r / w);
  EXPECT_NEAR(e[0].dq_peak, r, tolerance * r);
  EXPECT_NEAR(e[0].ddq_peak, r * w, tolerance * r * w);
  // q peaks where a sin(w t) - b cos(w t) = r, i.e. w t = atan2(a, -b) (mod 2 pi / l periods).
  const double phase = std::atan2(a, -b);
  const double t_max = std::fmod(phase / w + period, period / l);
  EXPECT_NEAR(std::fmod(e[0].q_max_time, period / l), t_max, period / 1000 / l);
}

TEST(LimitUse, GridIsAtLeastAThousandPointsPerHighestHarmonic) {
  EXPECT_EQ(limit_grid_points(one_harmonic(10, 0, 5, 1, 0)), 10000);
  EXPECT_EQ(limit_grid_points(one_harmonic(2, 0, 5, 1, 0)), 5000);
  EXPECT_EQ(limit_grid_points(one_harmonic(2, 0, 5, 1, 0), 4000), 8000);
}

TEST(LimitUse, PositionUseIsMeasuredFromTheMiddleOfTheRange) {
  // q in [0.4 - 0.3, 0.4 + 0.3] (velocity amplitude 0.3 w): against [-1, 0.6] (middle -0.2,
  // half range 0.8) the upper side is used most, (0.7 - (-0.2)) / 0.8 = 1.125.
  const double period = 4, w = 2 * std::numbers::pi / period;
  const FourierTrajectory x = one_harmonic(period, 0.4, 1, 0.3 * w, 0);
  JointLimits limits;
  limits.q_lower = -1;
  limits.q_upper = 0.6;
  limits.dq = 1.0;
  const std::vector<LimitUse> uses = limit_uses(trajectory_extremes(x), {limits});
  ASSERT_EQ(uses.size(), 2u);  // no ddq limit: left out
  EXPECT_EQ(uses[0].key, "q");
  EXPECT_NEAR(uses[0].value, 0.7, 1e-6);
  EXPECT_EQ(uses[0].limit, 0.6);
  EXPECT_NEAR(uses[0].use, 1.125, 1e-5);
  EXPECT_EQ(uses[1].key, "dq");
  EXPECT_NEAR(uses[1].use, 0.3 * w, 1e-5);
  const auto missing = missing_limits({limits});
  ASSERT_EQ(missing.size(), 1u);
  EXPECT_EQ(missing[0].second, "ddq");
}

}  // namespace
}  // namespace modelgen
