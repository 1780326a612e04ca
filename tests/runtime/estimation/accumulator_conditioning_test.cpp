// The streamed least squares (LeastSquaresAccumulator, fit_wls) on an ill-conditioned problem,
// against a dense SVD solution computed here: the reduction is orthogonal, so its error grows
// with cond(W), where normal equations (computed here too) lose cond(W)^2 and fail.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/SVD>

#include "modelgen/estimation/accumulator.hpp"
#include "modelgen/estimation/least_squares.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

constexpr int kColumns = 9, kGroups = 4;

// Rows in 4 interleaved groups. Column 3 is column 2 plus 1e-7 of another direction and the
// columns span 1e-2..1e2: cond(W) ~ 1e9 before scaling, ~1e7 after. Groups see different column
// sets (factor widths 10, 7, 9 and 4 with y: every remainder of the 4-column panels) and group
// 1 sees column 8 only in its second half (a column joining after reductions). The noise is
// small (1e-6 relative) so that the solution itself is well defined to ~1e-9.
struct Problem {
  Eigen::MatrixXd W;
  Eigen::VectorXd y;
  std::vector<int> group;
  std::vector<std::string> names;
};

Problem ill_conditioned(Eigen::Index rows) {
  test::Random random(21);
  Problem p;
  p.W.resize(rows, kColumns);
  p.y.resize(rows);
  p.group.resize(static_cast<std::size_t>(rows));
  Eigen::VectorXd beta = random.vector(kColumns, -2, 2);
  const double noise[kGroups] = {1e-6, 3e-6, 1e-5, 2e-6};
  for (Eigen::Index r = 0; r < rows; ++r) {
    const int g = static_cast<int>((r * 5 + r / 7) % kGroups);
    p.group[static_cast<std::size_t>(r)] = g;
    for (int k = 0; k < kColumns; ++k) p.W(r, k) = random.uniform(-1, 1);
    p.W(r, 3) = p.W(r, 2) + 1e-7 * random.uniform(-1, 1);
    for (int k = 0; k < kColumns; ++k) p.W(r, k) *= std::pow(10.0, 2.0 - k / 2.0);
    if (g == 1) p.W(r, 0) = p.W(r, 4) = p.W(r, 5) = 0;  // 6 columns seen
    if (g == 1 && r < rows / 2) p.W(r, 8) = 0;          // column 8 joins late
    if (g == 2) p.W(r, 7) = 0;                          // 8 columns seen
    if (g == 3) {
      for (int k : {0, 1, 4, 5, 6, 7}) p.W(r, k) = 0;  // 3 columns seen: 2, 3 and 8
    }
    p.y[r] = p.W.row(r).dot(beta) + noise[g] * random.normal();
  }
  for (int k = 0; k < kColumns; ++k) p.names.push_back("p" + std::to_string(k));
  return p;
}

struct Dense {
  Eigen::VectorXd value, std_dev;
  std::vector<double> group_std_dev;
  Eigen::MatrixXd weighted_W;
  Eigen::VectorXd weighted_y;
};

// Eq. 20 by SVD of the dense matrices: each group's OLS on the columns it sees gives sigma_g,
// then the rows weighted by 1 / sigma_g; covariance sigma^2 V S^-2 V^T (eq. 18).
Dense dense_wls(const Problem& p) {
  Dense out;
  std::vector<double> weight(p.group.size());
  for (int g = 0; g < kGroups; ++g) {
    std::vector<Eigen::Index> rows, seen;
    for (Eigen::Index r = 0; r < p.W.rows(); ++r) {
      if (p.group[static_cast<std::size_t>(r)] == g) rows.push_back(r);
    }
    for (Eigen::Index k = 0; k < kColumns; ++k) {
      if ((p.W(rows, k).array() != 0).any()) seen.push_back(k);
    }
    const Eigen::MatrixXd A = p.W(rows, seen);
    const Eigen::VectorXd b = p.y(rows);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const double squares = (b - A * svd.solve(b)).squaredNorm();
    const double sigma = std::sqrt(squares / static_cast<double>(rows.size() - seen.size()));
    out.group_std_dev.push_back(sigma);
    for (Eigen::Index r : rows) weight[static_cast<std::size_t>(r)] = 1 / sigma;
  }
  const Eigen::Map<const Eigen::VectorXd> w(weight.data(),
                                            static_cast<Eigen::Index>(weight.size()));
  out.weighted_W = w.asDiagonal() * p.W;
  out.weighted_y = w.cwiseProduct(p.y);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(out.weighted_W,
                                              Eigen::ComputeThinU | Eigen::ComputeThinV);
  out.value = svd.solve(out.weighted_y);
  const double variance = (out.weighted_y - out.weighted_W * out.value).squaredNorm() /
                          static_cast<double>(p.W.rows() - kColumns);
  const Eigen::VectorXd inverse_squares = svd.singularValues().cwiseInverse().cwiseAbs2();
  out.std_dev = (variance * (svd.matrixV().cwiseAbs2() * inverse_squares)).cwiseSqrt();
  return out;
}

void expect_agrees(const LeastSquaresResult& fit, const Dense& dense, const std::string& what) {
  EXPECT_LT(test::relative_error(fit.value, dense.value), 1e-7) << what;
  EXPECT_LT(test::relative_error(fit.std_dev, dense.std_dev), 1e-7) << what;
  ASSERT_EQ(fit.group_std_dev.size(), dense.group_std_dev.size()) << what;
  for (std::size_t g = 0; g < dense.group_std_dev.size(); ++g) {
    EXPECT_NEAR(fit.group_std_dev[g] / dense.group_std_dev[g], 1.0, 1e-7) << what << " group " << g;
  }
}

TEST(AccumulatorConditioning, IllConditionedWlsMatchesDenseSvd) {
  const Problem p = ill_conditioned(24000);
  const Dense dense = dense_wls(p);

  // The problem is as ill-conditioned as intended: normal equations in double, on the same
  // weighted rows, are off by far more than the tolerance the orthogonal reduction meets.
  const Eigen::MatrixXd normal = dense.weighted_W.transpose() * dense.weighted_W;
  const Eigen::VectorXd normal_value =
      normal.ldlt().solve(dense.weighted_W.transpose() * dense.weighted_y);
  EXPECT_GT(test::relative_error(normal_value, dense.value), 1e-5);

  expect_agrees(fit_wls(p.W, p.y, p.group, p.names), dense, "fit_wls");

  // Rows regrouped per group, row-major, fed in blocks of odd sizes (row counts off every
  // multiple of the reduction's chunks), then each group's residual norm for several betas.
  LeastSquaresAccumulator streamed(kColumns, kGroups);
  std::vector<std::vector<Eigen::Index>> members(kGroups);
  for (Eigen::Index r = 0; r < p.W.rows(); ++r)
    members[static_cast<std::size_t>(p.group[static_cast<std::size_t>(r)])].push_back(r);
  test::Random random(3);
  for (int g = 0; g < kGroups; ++g) {
    const std::vector<Eigen::Index>& m = members[static_cast<std::size_t>(g)];
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows =
        p.W(m, Eigen::all);
    const Eigen::VectorXd y = p.y(m);
    for (Eigen::Index start = 0; start < rows.rows();) {
      const Eigen::Index count = std::min<Eigen::Index>(
          rows.rows() - start, 1 + static_cast<Eigen::Index>(random.uniform(0, 300)));
      streamed.add(g, count, rows.data() + start * kColumns, kColumns, 1, y.data() + start, 1);
      start += count;
    }
  }
  expect_agrees(streamed.fit_wls(p.names), dense, "accumulator");
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd beta =
        trial == 0 ? dense.value : Eigen::VectorXd(random.vector(kColumns, -3, 3));
    for (int g = 0; g < kGroups; ++g) {
      const std::vector<Eigen::Index>& m = members[static_cast<std::size_t>(g)];
      const double direct = (p.y(m) - p.W(m, Eigen::all) * beta).norm();
      EXPECT_NEAR(streamed.residual_norm(g, beta) / direct, 1.0, trial == 0 ? 1e-6 : 1e-12)
          << "group " << g << ", beta " << trial;
    }
  }
}

}  // namespace
}  // namespace modelgen
