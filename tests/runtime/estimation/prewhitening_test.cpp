// The AR(1) prewhitening coefficient of correlated_covariance.hpp (issue 31): on an AR(1)
// sequence it is rho; on the same sequence with its slow part taken out, as a fit takes the
// noise on its slow columns out of a residual, it stays near rho while the lag-1
// autocorrelation g1 / g0 falls.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "runtime/src/estimation/correlated_covariance.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::detail {
namespace {

// The autocovariance at `lag`, a mean over its products.
double lagged(const Eigen::VectorXd& x, Eigen::Index lag) {
  const Eigen::Index n = x.size();
  return x.tail(n - lag).dot(x.head(n - lag)) / static_cast<double>(n - lag);
}

// The coefficient with K from the lag-1 autocorrelation, as identify() takes it.
double coefficient_of(const Eigen::VectorXd& x) {
  const Eigen::Index K = prewhitening_lag(lagged(x, 1) / lagged(x, 0), x.size());
  return prewhitening_coefficient(lagged(x, 0), lagged(x, 1), lagged(x, K), lagged(x, K + 1));
}

TEST(Prewhitening, IsRhoOnAnAr1Sequence) {
  constexpr Eigen::Index kRows = 200000;
  test::Random random(7);
  Eigen::VectorXd e(kRows);
  double state = 0;
  for (Eigen::Index t = 0; t < kRows; ++t) e[t] = state = 0.95 * state + random.normal();
  EXPECT_NEAR(coefficient_of(e), 0.95, 0.003);
  EXPECT_EQ(prewhitening_lag(0.95, kRows), 20);
  EXPECT_EQ(prewhitening_lag(0.95, 100), 5);  // at most rows / 20
  EXPECT_EQ(prewhitening_lag(-0.3, kRows), 1);
  // White noise: nothing to take out; a negative coefficient is not taken.
  Eigen::VectorXd w(kRows);
  for (Eigen::Index t = 0; t < kRows; ++t) w[t] = random.normal();
  EXPECT_LT(coefficient_of(w), 0.01);
  EXPECT_EQ(prewhitening_coefficient(1.0, -0.5, -0.5, 0.25), 0.0);
  EXPECT_EQ(prewhitening_coefficient(1.0, 1.0, 1.0, 1.0), 0.0);  // no change: no estimate
}

TEST(Prewhitening, KeepsRhoWhenAFitTookTheSlowNoise) {
  // 10 000 rows of AR(1) noise, 0.95, minus its least-squares fit on 60 slow sinusoids (the
  // lowest 30 lines of the record): about a quarter of its energy (60 of 256 independent rows'
  // worth) goes, and with it g1 / g0 drops to about 0.93.
  constexpr Eigen::Index kRows = 10000;
  test::Random random(8);
  double coefficient = 0, squares = 0, naive = 0;
  constexpr int kRuns = 20;
  for (int run = 0; run < kRuns; ++run) {
    Eigen::VectorXd e(kRows);
    double state = 0;
    for (Eigen::Index t = 0; t < kRows; ++t) e[t] = state = 0.95 * state + random.normal();
    Eigen::MatrixXd X(kRows, 60);
    for (Eigen::Index t = 0; t < kRows; ++t) {
      for (int l = 0; l < 30; ++l) {
        const double angle = 2 * std::numbers::pi * (l + 1) * static_cast<double>(t) / kRows;
        X(t, 2 * l) = std::cos(angle);
        X(t, 2 * l + 1) = std::sin(angle);
      }
    }
    const Eigen::VectorXd r = e - X * X.colPivHouseholderQr().solve(e);
    const double c = coefficient_of(r);
    coefficient += c / kRuns;
    squares += c * c / kRuns;
    naive += lagged(r, 1) / lagged(r, 0) / kRuns;
  }
  // 1 / (1 - c)^2 recolours the meat: c must be within a few thousandths on average, and run
  // by run within about 0.006 (g0 - gK of 256 independent rows' worth: 1 - c to 12 %; the
  // lag-1 form (g1 - g2) / (g0 - g1) spread 0.02).
  EXPECT_NEAR(coefficient, 0.95, 0.003);
  EXPECT_LT(std::sqrt(squares - coefficient * coefficient), 0.008);
  EXPECT_LT(naive, 0.945);
}

}  // namespace
}  // namespace modelgen::detail
