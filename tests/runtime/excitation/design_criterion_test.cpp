// most_collinear_pair: the pair it names and the floor it gives, against singular values
// computed here (JacobiSVD): exact for two columns, and below cond(W D) for every column
// scaling D tried.

#include "modelgen/excitation/design_criterion.hpp"

#include <cmath>

#include <Eigen/SVD>
#include <gtest/gtest.h>

#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

double cond(const Eigen::MatrixXd& M) {
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(M).singularValues();
  return s[0] / s[s.size() - 1];
}

TEST(MostCollinearPair, TwoColumnsAt45DegreesHaveCondOnePlusRootTwo) {
  Eigen::MatrixXd W(3, 3);
  W << 1, 3, 0,
       0, 3, 0,
       0, 0, 2;  // columns 0 and 1 at 45 degrees, column 2 orthogonal to both
  const CollinearPair pair = most_collinear_pair(W);
  EXPECT_EQ(pair.first, 0);
  EXPECT_EQ(pair.second, 1);
  EXPECT_NEAR(pair.correlation, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(pair.cond_floor, 1 + std::sqrt(2.0), 1e-12);
  Eigen::MatrixXd unit = W.leftCols(2);
  unit.col(0).normalize(), unit.col(1).normalize();
  EXPECT_NEAR(cond(unit), pair.cond_floor, 1e-12);
}

TEST(MostCollinearPair, NoColumnScalingGoesBelowTheFloor) {
  test::Random random(21);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::MatrixXd W(40, 6);
    for (Eigen::Index c = 0; c < W.cols(); ++c) W.col(c) = random.vector(40, -1.0, 1.0);
    W.col(4) += 3 * W.col(1);  // one strongly collinear pair
    const CollinearPair pair = most_collinear_pair(W);
    EXPECT_EQ(pair.first, 1);
    EXPECT_EQ(pair.second, 4);
    for (int scaling = 0; scaling < 50; ++scaling) {
      const Eigen::VectorXd d = random.vector(6, -3.0, 3.0).array().exp();
      EXPECT_GE(cond(W * d.asDiagonal()), pair.cond_floor * (1 - 1e-12));
    }
  }
}

}  // namespace
}  // namespace modelgen
