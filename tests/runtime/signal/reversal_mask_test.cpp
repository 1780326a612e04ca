// reversal_mask (issue 31): which torque equations are weighted down near a reversal, against
// closed forms, and that weighting both sides before the parallel decimation keeps equations
// exact where leaving out decimated rows does not.

#include "modelgen/signal/reversal_mask.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "modelgen/signal/decimation.hpp"

namespace modelgen {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(ReversalMask, ZeroWhereSlowRisingOverTheGuard) {
  // One joint reversing at sample 500: dq = (s - 500) / 1000, slower than 0.01 for |s - 500| < 10.
  const Eigen::Index m = 1000, guard = 40;
  Eigen::MatrixXd dq(m, 1);
  for (Eigen::Index s = 0; s < m; ++s) dq(s, 0) = (static_cast<double>(s) - 500) / 1000;
  const Eigen::ArrayXXd mask =
      reversal_mask(dq, Eigen::MatrixXd::Identity(1, 1), Eigen::VectorXd::Constant(1, 0.01), guard);
  for (Eigen::Index s = 0; s < m; ++s) {
    const Eigen::Index d = std::max<Eigen::Index>(0, std::abs(s - 500) - 9);  // to the slow run
    const double expected =
        d > guard ? 1.0 : 0.5 - 0.5 * std::cos(kPi * static_cast<double>(d) / (guard + 1));
    EXPECT_NEAR(mask(s, 0), expected, 1e-15) << "sample " << s;
  }
  EXPECT_EQ(mask(495, 0), 0.0);
  EXPECT_EQ(mask(100, 0), 1.0);
}

TEST(ReversalMask, CoupledMotorWeighsTheJointsItDrives) {
  // Motor 2 drives joints 1 and 2 (K row 2 = [0.5, 1]): when it is slow (dq2 = -0.5 dq1),
  // equations 1 and 2 are left out although neither joint is slow; equation 3 is not.
  Eigen::MatrixXd K = Eigen::MatrixXd::Identity(3, 3);
  K(1, 0) = 0.5;
  Eigen::MatrixXd dq = Eigen::MatrixXd::Constant(5, 3, 1.0);
  dq.row(2) << 1.0, -0.5, 1.0;
  const Eigen::ArrayXXd mask = reversal_mask(dq, K, Eigen::VectorXd::Constant(3, 0.1), 0);
  for (Eigen::Index s = 0; s < 5; ++s) {
    EXPECT_EQ(mask(s, 0), s == 2 ? 0.0 : 1.0) << s;
    EXPECT_EQ(mask(s, 1), s == 2 ? 0.0 : 1.0) << s;
    EXPECT_EQ(mask(s, 2), 1.0) << s;
  }
}

TEST(ReversalMask, NoSpeedsKeepEverythingAndBadSizesThrow) {
  const Eigen::MatrixXd dq = Eigen::MatrixXd::Zero(4, 2);
  const Eigen::MatrixXd K = Eigen::MatrixXd::Identity(2, 2);
  EXPECT_TRUE((reversal_mask(dq, K, Eigen::VectorXd(), 3) == 1.0).all());
  EXPECT_THROW(reversal_mask(dq, K, Eigen::VectorXd::Ones(3), 3), std::invalid_argument);
  EXPECT_THROW(reversal_mask(dq, K, Eigen::VectorXd::Ones(2), -1), std::invalid_argument);
  EXPECT_EQ(reversal_guard_samples(6.1, 1000.0), 328);  // two periods of the cut-off
  EXPECT_EQ(reversal_guard_samples(0.0, 1000.0), 0);
}

TEST(ReversalMask, WeightedEquationsStayExactThroughTheDecimation) {
  // tau = W beta everywhere except near a reversal, where a sticking joint's friction is
  // anything (here random). Decimated rows whose own decimated speed is fast still carry that
  // error from their filter window; weighting both sides first leaves none.
  const Eigen::Index m = 4000, b = 3;
  const int factor = 40;
  std::mt19937_64 engine(5);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd dq(m, 1), W(m, b);
  Eigen::VectorXd beta(b), tau(m);
  beta << 1.0, -2.0, 0.5;
  for (Eigen::Index s = 0; s < m; ++s) {
    const double t = static_cast<double>(s) / 1000;
    dq(s, 0) = std::sin(2 * kPi * 0.5 * t);
    W.row(s) << std::cos(2 * kPi * 0.3 * t), t, std::sin(2 * kPi * 0.7 * t);
    tau[s] = W.row(s).dot(beta);
    if (std::abs(dq(s, 0)) < 0.05) tau[s] += 3 * normal(engine);  // stick: not W beta
  }
  const Eigen::ArrayXXd mask =
      reversal_mask(dq, Eigen::MatrixXd::Identity(1, 1), Eigen::VectorXd::Constant(1, 0.05), 80);
  const Eigen::MatrixXd Wm = mask.col(0).matrix().asDiagonal() * W;
  const Eigen::VectorXd taum = mask.col(0).matrix().cwiseProduct(tau);
  const Eigen::MatrixXd Wd = decimate_interior(Wm, factor), td = decimate_interior(taum, factor);
  EXPECT_LT((td - Wd * beta).cwiseAbs().maxCoeff(), 1e-10);
  // Without the weights, the decimated rows that pass a speed test on the decimated dq.
  const Eigen::MatrixXd Wr = decimate_interior(W, factor), tr = decimate_interior(tau, factor);
  const Eigen::MatrixXd dqd = decimate_interior(dq, factor);
  double worst = 0;
  for (Eigen::Index r = 0; r < dqd.rows(); ++r) {
    if (std::abs(dqd(r, 0)) >= 0.05)
      worst = std::max(worst, std::abs(tr(r, 0) - Wr.row(r).dot(beta)));
  }
  EXPECT_GT(worst, 1e-3);
}

}  // namespace
}  // namespace modelgen
