// The fast evaluations of a Fourier excitation against the direct sum of its terms (Swevers
// eq. 15-17, one std::sin and std::cos per term): FourierTrajectory::evaluate at random times
// (to the bit) and the FFT blocks of the limit grid at its points (to 1e-9 of the sum of the
// amplitudes), up to 1000 harmonics; and a limit violation that peaks between the points of a
// coarse grid, which the limit grid must still see.

#include "runtime/src/excitation/fourier_grid.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "modelgen/excitation/limit_use.hpp"

namespace modelgen {
namespace {

FourierTrajectory random_trajectory(int dof, int harmonics, double period, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  FourierTrajectory x;
  x.period = period;
  x.q0 = Eigen::VectorXd::NullaryExpr(dof, [&] { return coefficient(random); });
  x.a = Eigen::MatrixXd::NullaryExpr(dof, harmonics, [&] { return coefficient(random); });
  x.b = Eigen::MatrixXd::NullaryExpr(dof, harmonics, [&] { return coefficient(random); });
  return x;
}

// q, dq, ddq of joint j at t, term by term, as FourierTrajectory::evaluate used to.
Eigen::Vector3d direct(const FourierTrajectory& x, Eigen::Index j, double t) {
  const double wf = 2.0 * std::numbers::pi / x.period;
  Eigen::Vector3d v(x.q0[j], 0.0, 0.0);
  for (Eigen::Index l = 0; l < x.a.cols(); ++l) {
    const double w = wf * static_cast<double>(l + 1);
    const double s = std::sin(w * t), c = std::cos(w * t);
    v[0] += x.a(j, l) / w * s - x.b(j, l) / w * c;
    v[1] += x.a(j, l) * c + x.b(j, l) * s;
    v[2] += -x.a(j, l) * w * s + x.b(j, l) * w * c;
  }
  return v;
}

// Relative to the sums of the terms' amplitudes (what a sum of that many terms is rounded
// against): 1e-9 of it.
void expect_equal(const FourierTrajectory& x, Eigen::Index j, double t,
                  const Eigen::Vector3d& got) {
  const detail::SeriesBounds bound = detail::series_bounds(x);
  const Eigen::Vector3d want = direct(x, j, t);
  EXPECT_NEAR(got[0], want[0], 1e-9 * (bound.q[j] + std::abs(x.q0[j]))) << "q at t = " << t;
  EXPECT_NEAR(got[1], want[1], 1e-9 * bound.dq[j]) << "dq at t = " << t;
  EXPECT_NEAR(got[2], want[2], 1e-9 * bound.ddq[j]) << "ddq at t = " << t;
}

// evaluate() shares each harmonic's sine and cosine between the joints; the values must stay
// those of the term-by-term sum to the bit (the bundled data sets are compared byte for byte).
TEST(FourierGrid, EvaluateIsTheDirectSumToTheBit) {
  for (int harmonics : {1, 2, 17, 1000}) {
    const FourierTrajectory x = random_trajectory(3, harmonics, 7.3, 10u + harmonics);
    std::mt19937 random(harmonics);
    std::uniform_real_distribution<double> time(0.0, 50 * x.period);
    Eigen::VectorXd q, dq, ddq;
    for (int k = 0; k < 100; ++k) {
      const double t = time(random);
      x.evaluate(t, q, dq, ddq);
      for (Eigen::Index j = 0; j < 3; ++j) {
        EXPECT_EQ(Eigen::Vector3d(q[j], dq[j], ddq[j]), direct(x, j, t)) << "t = " << t;
      }
    }
  }
}

TEST(FourierGrid, BlocksAreDivisorsWithTheFftsRadices) {
  for (long n : {1L, 7L, 1000L, 36960L, 1000000L, 1000003L, 999983L, 4096L * 3 * 25}) {
    const long m = detail::grid_block(n);
    EXPECT_EQ(n % m, 0) << n;
    EXPECT_LE(m, detail::kMaxGridBlock) << n;
    long rest = m;
    for (long p : {2L, 3L, 5L}) {
      while (rest % p == 0) rest /= p;
    }
    EXPECT_EQ(rest, 1) << n << ": block " << m;
  }
  EXPECT_EQ(detail::grid_block(1000000), 8000);
}

TEST(FourierGrid, TheLimitGridKeepsItsRuleAndBlocksOfAtLeastAnEighthOfTheHarmonics) {
  for (double period : {0.5, 10.0, 36.96, 1000.003, 2000.0017}) {
    for (int harmonics : {1, 5, 999, 1000}) {
      const FourierTrajectory x = random_trajectory(1, harmonics, period, 1u);
      const long n = limit_grid_points(x);
      EXPECT_GE(n, 1000L * harmonics);
      EXPECT_GE(n, static_cast<long>(std::ceil(period * 1000)));
      // Rounded up by fewer than 2 L points.
      EXPECT_LT(n, std::max<long>(1000L * harmonics, std::ceil(period * 1000)) + 2 * harmonics);
      EXPECT_GE(8 * detail::grid_block(n), harmonics) << period << " s, " << harmonics;
    }
  }
}

// Every grid point once, each equal to the direct sum; n of several shapes (blocks of one
// point for a prime n, blocks shorter and longer than L).
TEST(FourierGrid, BlocksEqualTheDirectSumAtTheGridPoints) {
  struct Case {
    int harmonics;
    long n;
  };
  for (const Case c : {Case{3, 10007}, Case{3, 7 * 11 * 13}, Case{40, 2000}, Case{1000, 1000000}}) {
    const FourierTrajectory x = random_trajectory(2, c.harmonics, 3.7, 5u);
    std::mt19937 random(c.harmonics);
    std::set<long> checked;
    for (int k = 0; k < 300; ++k)
      checked.insert(std::uniform_int_distribution<long>(0, c.n - 1)(random));
    std::vector<int> seen(static_cast<std::size_t>(c.n), 0);
    detail::for_each_grid_block(x, c.n, [&](const detail::GridBlock& block) {
      for (Eigen::Index k = 0; k < block.q.rows(); ++k) {
        const long s = block.index(k);
        ASSERT_GE(s, 0);
        ASSERT_LT(s, c.n);
        ++seen[static_cast<std::size_t>(s)];
        if (checked.count(s) == 0) continue;
        const double t = x.period * static_cast<double>(s) / static_cast<double>(c.n);
        for (Eigen::Index j = 0; j < 2; ++j) {
          expect_equal(x, j, t, Eigen::Vector3d(block.q(k, j), block.dq(k, j), block.ddq(k, j)));
        }
      }
    });
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), c.n) << "n = " << c.n;
  }
}

// q(t) = A sum_{l=1..1000} cos(l wf (t - t0)): a spike of height 1000 A at t0, a millisecond
// wide, between two points of a 1 kHz grid where it is small. Velocity amplitudes:
// a_l = A w sin(w t0), b_l = -A w cos(w t0).
TEST(FourierGrid, AViolationPeakingBetweenCoarseGridPointsIsFound) {
  const int harmonics = 1000;
  const double period = 1.0, t0 = 0.0004567, amplitude = 1e-3;
  FourierTrajectory x;
  x.period = period;
  x.q0 = Eigen::VectorXd::Zero(1);
  x.a.resize(1, harmonics);
  x.b.resize(1, harmonics);
  const double wf = 2 * std::numbers::pi / period;
  for (int l = 1; l <= harmonics; ++l) {
    const double w = l * wf;
    x.a(0, l - 1) = amplitude * w * std::sin(w * t0);
    x.b(0, l - 1) = -amplitude * w * std::cos(w * t0);
  }
  const double peak = harmonics * amplitude;
  // On the 1 kHz grid alone, the spike does not reach half its height.
  double coarse = -1e9;
  Eigen::VectorXd q, dq, ddq;
  for (int k = 0; k < 1000; ++k) {
    x.evaluate(period * k / 1000.0, q, dq, ddq);
    coarse = std::max(coarse, q[0]);
  }
  ASSERT_LT(coarse, 0.5 * peak);

  const std::vector<JointExtremes> e = trajectory_extremes(x);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_GE(e[0].q_max, peak * (1 - 5e-6));
  EXPECT_LE(e[0].q_max, peak * (1 + 1e-12));
  EXPECT_NEAR(e[0].q_max_time, t0, period / static_cast<double>(limit_grid_points(x)));
  JointLimits limit;
  limit.q_lower = -0.5 * peak;
  limit.q_upper = 0.5 * peak;
  const std::vector<LimitUse> uses = limit_uses(e, {limit});
  ASSERT_EQ(uses.size(), 1u);
  EXPECT_EQ(uses[0].key, "q");
  EXPECT_GT(uses[0].use, 1.9);
}

}  // namespace
}  // namespace modelgen
