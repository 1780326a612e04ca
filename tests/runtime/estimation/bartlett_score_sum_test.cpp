// The Bartlett lag sum of correlated_covariance.hpp taken by overlapping batch means (issue 31)
// against the Newey-West sum written out lag by lag here, and the Andrews bandwidth against its
// closed form.

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "runtime/src/estimation/correlated_covariance.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::detail {
namespace {

// sum_|l|<=L (1 - |l| / (L + 1)) sum_t g_t g_(t-l)^T, directly.
Eigen::MatrixXd newey_west(const Eigen::MatrixXd& G, int L) {
  Eigen::MatrixXd meat = G.transpose() * G;
  const Eigen::Index n = G.rows();
  for (int l = 1; l <= L; ++l) {
    const Eigen::MatrixXd lagged = G.bottomRows(n - l).transpose() * G.topRows(n - l);
    meat += (1.0 - l / (L + 1.0)) * (lagged + lagged.transpose());
  }
  return meat;
}

// An AR(1) score sequence: the lags matter.
Eigen::MatrixXd correlated_scores(Eigen::Index n, Eigen::Index b, double rho, unsigned seed) {
  test::Random random(seed);
  Eigen::MatrixXd G(n, b);
  Eigen::VectorXd state = Eigen::VectorXd::Zero(b);
  for (Eigen::Index t = 0; t < n; ++t) {
    for (Eigen::Index k = 0; k < b; ++k) state[k] = rho * state[k] + random.normal();
    G.row(t) = state.transpose();
  }
  return G;
}

Eigen::MatrixXd batch_means(const Eigen::MatrixXd& G, int L) {
  BartlettScoreSum sum(G.cols(), L);
  for (Eigen::Index t = 0; t < G.rows(); ++t) sum.add(G.row(t).transpose());
  EXPECT_EQ(sum.rows(), G.rows());
  return sum.meat();
}

// Away from the ends both weigh lag l by 1 - l / (L + 1): on a long sequence they agree to the
// share of the rows within L of an end.
TEST(BartlettScoreSum, AgreesWithTheLagByLagSum) {
  const Eigen::MatrixXd G = correlated_scores(20000, 4, 0.9, 7);
  for (int L : {0, 1, 5, 40, 300}) {
    const Eigen::MatrixXd direct = newey_west(G, L), streamed = batch_means(G, L);
    const double tolerance = 4.0 * (L + 1) / G.rows() + 1e-12;
    EXPECT_LT((streamed - direct).norm() / direct.norm(), tolerance) << "L = " << L;
  }
}

// With L = 0 it is the plain sum of outer products, to rounding, across the block boundary.
TEST(BartlettScoreSum, WithoutLagsIsTheSumOfOuterProducts) {
  const Eigen::MatrixXd G = correlated_scores(1000, 3, 0.5, 8);
  const Eigen::MatrixXd direct = G.transpose() * G;
  EXPECT_LT((batch_means(G, 0) - direct).norm(), 1e-10 * direct.norm());
}

// Andrews (1991) eq. 6.4, AR(1) plug-in: L = 1.1447 (alpha n)^(1/3),
// alpha = 4 rho^2 / ((1 - rho)^2 (1 + rho)^2); white residuals need no sandwich.
TEST(ResidualCorrelation, SignificanceAndBandwidth) {
  const double rho = 0.95, rows = 60000, sequences = 6;
  const Correlation c = residual_correlation(rho * rows, rows, 60000, 6);
  const double alpha = 4 * rho * rho / std::pow((1 - rho) * (1 + rho), 2);
  EXPECT_TRUE(c.significant);
  EXPECT_EQ(c.bandwidth, static_cast<int>(std::ceil(1.1447 * std::cbrt(alpha * rows / sequences))));
  // 0.01 over 60 000 rows is 2.4 sd of a white sequence's, and under 0.05 anyway.
  EXPECT_FALSE(residual_correlation(0.01 * rows, rows, 60000, 6).significant);
  // 0.08 over 100 rows is under 3 sd (0.3).
  EXPECT_FALSE(residual_correlation(0.08 * 100, 100, 100, 1).significant);
}

}  // namespace
}  // namespace modelgen::detail
