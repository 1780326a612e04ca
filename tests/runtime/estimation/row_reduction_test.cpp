// fold_rows, the accumulator's kernel, against the definition of the factor: R^T R of the
// result equals [R0; B]^T [R0; B] (Gram matrix in long double, computed here), R stays upper
// triangular, and NaN in the rows reaches R.

#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "runtime/src/estimation/row_reduction.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

TEST(RowReduction, FactorHasTheGramMatrixOfTheStack) {
  test::Random random(7);
  // Widths around the 4-column panels and the 3-column passes, row counts off the 4-row
  // vectors and across the 256-row chunks; leading dimensions larger than the blocks.
  for (int w : {1, 2, 3, 4, 5, 7, 8, 9, 10, 13, 39}) {
    for (int m : {1, 3, 4, 9, 255, 256, 600}) {
      const Eigen::Index ld = w + m + 3;
      Eigen::MatrixXd S = Eigen::MatrixXd::Zero(ld, w);
      for (Eigen::Index j = 0; j < w; ++j) {
        for (Eigen::Index i = 0; i <= j; ++i) S(i, j) = random.uniform(-1, 1);
        for (Eigen::Index i = w; i < w + m; ++i) S(i, j) = random.uniform(-1, 1);
      }
      if (w > 2) S.block(w, 1, m, 1).setZero();  // a column already zero in the new rows
      LongMatrix gram = LongMatrix::Zero(w, w);
      for (Eigen::Index i = 0; i < w + m; ++i) {
        for (Eigen::Index a = 0; a < w; ++a) {
          for (Eigen::Index b = 0; b < w; ++b) {
            gram(a, b) += static_cast<long double>(S(i, a)) * S(i, b);
          }
        }
      }
      detail::fold_rows(S.data(), ld, S.data() + w, ld, m, w);
      const Eigen::MatrixXd R = S.topRows(w);
      const LongMatrix RtR = (R.transpose() * R).cast<long double>();
      const double scale = static_cast<double>(gram.cwiseAbs().maxCoeff());
      EXPECT_LT(static_cast<double>((RtR - gram).cwiseAbs().maxCoeff()), 1e-13 * scale)
          << "w " << w << ", m " << m;
      EXPECT_EQ(R.triangularView<Eigen::StrictlyLower>().toDenseMatrix().cwiseAbs().maxCoeff(), 0.0)
          << "w " << w << ", m " << m;
    }
  }
}

TEST(RowReduction, NanInTheRowsReachesTheFactor) {
  for (int w : {1, 6, 9}) {
    const Eigen::Index m = 300;
    Eigen::MatrixXd S = Eigen::MatrixXd::Ones(w + m, w);
    S.topRows(w).setZero();
    S(w + 257, w - 1) = std::numeric_limits<double>::quiet_NaN();
    detail::fold_rows(S.data(), S.rows(), S.data() + w, S.rows(), m, w);
    EXPECT_FALSE(S.topRows(w).allFinite()) << "w " << w;
  }
}

}  // namespace
}  // namespace modelgen
