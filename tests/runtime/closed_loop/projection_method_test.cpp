// Stage 1 of the projection method against a known truth: a torque made by a known non-causal
// FIR of two white references plus independent white noise. The FIR is recovered within its
// least-squares uncertainty, the chosen M covers the true support and no more than the next
// step of the ladder, u^ is near the noise-free torque, the discarded fraction near the noise's
// share; a too-small M fails the decorrelation test.

#include "modelgen/closed_loop/projection_method.hpp"

#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

constexpr Eigen::Index kFirstRow = 200, kSamples = 4000, kTotal = 4400;
constexpr double kConstant = 0.5, kNoise = 0.3;
// The true FIR: lag k -> coefficient, support -2..3 on reference 1, -1..1 on reference 2.
const std::map<int, double> kFir1 = {{-2, 0.3}, {-1, -0.5}, {0, 1.0},
                                     {1, 0.7},  {2, -0.4},  {3, 0.4}};
const std::map<int, double> kFir2 = {{-1, 0.6}, {0, -0.8}, {1, 0.25}};

struct Synthetic {
  Eigen::MatrixXd qr, u, clean, noise;
};

Synthetic make_synthetic(std::uint64_t seed) {
  test::Random random(seed);
  Synthetic x;
  x.qr.resize(kTotal, 2);
  for (Eigen::Index s = 0; s < kTotal; ++s) x.qr.row(s) << random.normal(), random.normal();
  x.clean.resize(kSamples, 1);
  x.noise.resize(kSamples, 1);
  for (Eigen::Index s = 0; s < kSamples; ++s) {
    double value = kConstant;
    for (const auto& [k, h] : kFir1) value += h * x.qr(kFirstRow + s - k, 0);
    for (const auto& [k, h] : kFir2) value += h * x.qr(kFirstRow + s - k, 1);
    x.clean(s, 0) = value;
    x.noise(s, 0) = kNoise * random.normal();
  }
  x.u = x.clean + x.noise;
  return x;
}

double true_coefficient(const std::map<int, double>& fir, int k) {
  const auto it = fir.find(k);
  return it == fir.end() ? 0.0 : it->second;
}

TEST(ProjectionMethod, RecoversAKnownNonCausalFir) {
  const Synthetic x = make_synthetic(5);
  const int reach = decorrelation_window(32);
  const LaggedReferences references = lagged_references(x.qr, kFirstRow, kSamples, 1, false, reach);
  // The lagged references are the raw ones shifted (no decimation, no pairing).
  EXPECT_EQ(references.at(3)(10, 0), x.qr(kFirstRow + 10 - 3, 0));
  EXPECT_EQ(references.at(-2)(10, 1), x.qr(kFirstRow + 10 + 2, 1));

  const std::vector<int> ladder = fir_lag_ladder(kSamples, 2, reach);
  ASSERT_EQ(ladder.back(), 32);
  const FirChoice choice = choose_fir_projection({x.u}, {references}, ladder);
  // The support reaches lag 3: M = 2 misses it, M = 4 is the next step of the ladder.
  EXPECT_EQ(choice.lags, 4);
  EXPECT_TRUE(choice.decorrelated);
  const FirProjection& fir = choice.fits[0];
  ASSERT_TRUE(fir.full_rank);
  ASSERT_EQ(fir.moving, (std::vector<int>{0, 1}));
  ASSERT_EQ(fir.coefficients.rows(), 1 + 2 * 9);
  // Every coefficient, in or out of the support, within 4 of its standard deviations.
  EXPECT_LT(std::abs(fir.coefficients(0, 0) - kConstant), 4 * fir.coefficient_std(0, 0));
  for (int i = 0; i < 2; ++i) {
    for (int k = -4; k <= 4; ++k) {
      const Eigen::Index row = 1 + i * 9 + (k + 4);
      const double truth = true_coefficient(i == 0 ? kFir1 : kFir2, k);
      EXPECT_LT(std::abs(fir.coefficients(row, 0) - truth), 4 * fir.coefficient_std(row, 0))
          << "reference " << i + 1 << " lag " << k << ": " << fir.coefficients(row, 0) << " +- "
          << fir.coefficient_std(row, 0) << ", truth " << truth;
      // White references of unit variance: sd = noise / sqrt(N).
      EXPECT_NEAR(fir.coefficient_std(row, 0), kNoise / std::sqrt(double(kSamples)),
                  0.2 * kNoise / std::sqrt(double(kSamples)));
    }
  }
  // u^ keeps the noise's share in the 19 regressors' span only: ~ sqrt(19 / 4000) of it.
  EXPECT_LT((fir.projected - x.clean).norm(), 0.15 * x.noise.norm());
  // The discarded fraction is the noise's share, less the sliver the fit absorbs.
  const double discarded = std::sqrt(fir.residual_squares.sum()) / x.u.norm();
  const double noise_share = x.noise.norm() / x.u.norm();
  EXPECT_NEAR(discarded, noise_share, 0.03 * noise_share);
}

TEST(ProjectionMethod, TooFewLagsFailTheDecorrelationTest) {
  const Synthetic x = make_synthetic(6);
  const LaggedReferences references =
      lagged_references(x.qr, kFirstRow, kSamples, 1, false, decorrelation_window(4));
  const FirProjection fir = fit_fir_projection(x.u, references, 1);
  EXPECT_FALSE(fir.test.passed());
  EXPECT_GT(fir.test.worst, fir.test.band);
  // The residual keeps 0.3 r1(t+2), -0.4 r1(t-2), 0.4 r1(t-3): its correlation with them, about
  // 0.4 / sqrt(0.3^2 + 0.4^2 + 0.4^2 + 0.3^2) = 0.6, is far beyond the band.
  EXPECT_GT(fir.test.worst, 0.4);
  EXPECT_EQ(fir.test.worst_reference, 0);
  EXPECT_GE(std::abs(fir.test.worst_lag), 2);
  // Within M the correlation is zero by construction, so only M < |k| <= window is tested.
  EXPECT_EQ(fir.test.tested, 1LL * 2 * 2 * (decorrelation_window(1) - 1));
}

TEST(ProjectionMethod, RefusesMoreCoefficientsThanTheRowsCarry) {
  const Synthetic x = make_synthetic(7);
  const Eigen::MatrixXd u = x.u.topRows(300);
  const LaggedReferences references =
      lagged_references(x.qr, kFirstRow, 300, 1, false, decorrelation_window(32));
  EXPECT_THROW(fit_fir_projection(u, references, 32), EstimationError);
  EXPECT_EQ(fir_lag_ladder(300, 2, 100).back(), 4);  // 1 + 2 * 9 = 19 <= 30 rows each
}

}  // namespace
}  // namespace modelgen
