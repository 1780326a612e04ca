// Least squares with statistics (Gautier & Briot eq. 15-20) on simulated TX-40 data: the base
// regressor of the numeric reference along Fourier trajectories, torques from known physical
// parameters plus Gaussian noise of known level per joint. Noise-free data must give the
// parameters exactly; with noise the standard deviations must describe the actual errors.
// On small random problems every statistic is checked against the normal equations solved in
// long double (an independent computation, accurate there), for the whole-W fits and for the
// streaming accumulator fed in odd blocks, both layouts, and merged.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <random>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/SVD>

#include "modelgen/estimation/accumulator.hpp"
#include "modelgen/estimation/essential.hpp"
#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/least_squares.hpp"
#include "modelgen/model/base_parameters.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

// Gaussian numbers by Box-Muller on the portable uniform generator.
double gaussian(test::Random& random) {
  const double u = random.uniform(1e-300, 1.0), v = random.uniform(0.0, 1.0);
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * v);
}

class SimulatedTx40 : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    data_ = new Data();
    const modelgen::RobotModel model = modelgen::load_robot(test::source_path("robots/tx40.yaml"));
    const ReferenceDynamics reference(model.tree);
    const BaseParameterSet base = derive_base_parameters(model.tree);
    for (const BaseParameter& b : base.params) data_->names.push_back(b.name);
    test::Random random(1);
    data_->beta = base.K * test::random_physical_parameters(model.tree, random);
    // Five-harmonic Fourier trajectories (Swevers eq. 15) with a 10 s period, 1500 samples.
    const int n = 6, harmonics = 5, samples = 1500;
    const double wf = 2 * std::numbers::pi / 10.0;
    Eigen::MatrixXd a(n, harmonics), b(n, harmonics);
    for (int j = 0; j < n; ++j) {
      for (int l = 0; l < harmonics; ++l) {
        a(j, l) = random.uniform(-0.5, 0.5);
        b(j, l) = random.uniform(-0.5, 0.5);
      }
    }
    data_->W.resize(samples * n, base.params.size());
    data_->group.resize(samples * n);
    for (int s = 0; s < samples; ++s) {
      const double t = 10.0 * s / samples;
      Eigen::VectorXd q = Eigen::VectorXd::Zero(n), dq = q, ddq = q;
      for (int j = 0; j < n; ++j) {
        for (int l = 1; l <= harmonics; ++l) {
          const double w = wf * l, sn = std::sin(w * t), cs = std::cos(w * t);
          const double al = a(j, l - 1), bl = b(j, l - 1);
          q[j] += al / w * sn - bl / w * cs;
          dq[j] += al * cs + bl * sn;
          ddq[j] += -al * w * sn + bl * w * cs;
        }
      }
      const Eigen::MatrixXd W = reference.standard_regressor(q, dq, ddq);
      for (std::size_t k = 0; k < base.params.size(); ++k) {
        data_->W.block(s * n, k, n, 1) = W.col(base.params[k].standard_index);
      }
      for (int j = 0; j < n; ++j) data_->group[s * n + j] = j;
    }
    data_->tau = data_->W * data_->beta;
  }
  static void TearDownTestSuite() { delete data_; }

  struct Data {
    Eigen::MatrixXd W;
    Eigen::VectorXd beta, tau;
    std::vector<int> group;
    std::vector<std::string> names;
  };
  static Data* data_;
  static constexpr double kNoise[6] = {2.0, 2.0, 1.0, 0.3, 0.3, 0.1};  // N m per joint
};

SimulatedTx40::Data* SimulatedTx40::data_ = nullptr;

TEST_F(SimulatedTx40, NoiseFreeDataGiveTheExactParameters) {
  for (bool weighted : {false, true}) {
    const LeastSquaresResult fit = weighted
                                       ? fit_wls(data_->W, data_->tau, data_->group, data_->names)
                                       : fit_ols(data_->W, data_->tau, data_->names);
    EXPECT_LT(test::relative_error(fit.value, data_->beta), 1e-8) << (weighted ? "WLS" : "OLS");
    EXPECT_LT(fit.relative_error_norm, 1e-12);
  }
}

TEST_F(SimulatedTx40, StandardDeviationsDescribeTheErrorsOverTwentyNoiseSeeds) {
  int checked = 0, outside = 0;
  double normalized_square_sum = 0;
  for (int seed = 1; seed <= 20; ++seed) {
    test::Random random(1000 + seed);
    Eigen::VectorXd y = data_->tau;
    for (Eigen::Index r = 0; r < y.size(); ++r) y[r] += kNoise[data_->group[r]] * gaussian(random);
    const LeastSquaresResult fit = fit_wls(data_->W, y, data_->group, data_->names);
    // WLS recovers each joint's noise level (eq. 20).
    for (int j = 0; j < 6; ++j) {
      EXPECT_NEAR(fit.group_std_dev[j] / kNoise[j], 1.0, 0.1) << "joint " << j + 1;
    }
    for (Eigen::Index k = 0; k < fit.value.size(); ++k) {
      if (!(fit.rel_std_dev[k] < 10.0)) continue;  // well identified parameters only
      const double error = (fit.value[k] - data_->beta[k]) / fit.std_dev[k];
      ++checked;
      normalized_square_sum += error * error;
      if (std::abs(error) > 3.0) ++outside;
    }
  }
  ASSERT_GT(checked, 200);
  // Normalized errors should be standard normal: about 0.27 % beyond 3, mean square 1.
  EXPECT_LE(outside, checked / 100) << outside << " of " << checked << " beyond 3 sigma";
  EXPECT_NEAR(normalized_square_sum / checked, 1.0, 0.2);
}

TEST_F(SimulatedTx40, EssentialParametersMeetTheRatio) {
  test::Random random(77);
  Eigen::VectorXd y = data_->tau;
  for (Eigen::Index r = 0; r < y.size(); ++r) y[r] += kNoise[data_->group[r]] * gaussian(random);
  const EssentialParameters essential =
      essential_parameters(data_->W, y, data_->group, data_->names, 20.0);
  EXPECT_EQ(essential.kept.size() + essential.eliminated.size(), data_->names.size());
  EXPECT_LT(essential.fit.rel_std_dev.maxCoeff(), 20.0 * essential.fit.rel_std_dev.minCoeff());
  EXPECT_FALSE(essential.eliminated.empty());
}

TEST(Estimate, RankDeficiencyNamesTheParameters) {
  test::Random random(3);
  Eigen::MatrixXd W(50, 4);
  for (Eigen::Index r = 0; r < 50; ++r) {
    W(r, 0) = random.uniform(-1, 1);
    W(r, 1) = random.uniform(-1, 1);
    W(r, 2) = 2 * W(r, 0) - W(r, 1);  // moves with the first two
    W(r, 3) = 0;                      // never excited
  }
  const Eigen::VectorXd y = random.vector(50, -1, 1);
  try {
    fit_ols(W, y, {"ZZ1R", "Fv1", "XX2R", "Fc6"});
    ADD_FAILURE() << "rank-deficient W accepted";
  } catch (const EstimationError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("rank 2 of 4"), std::string::npos) << what;
    EXPECT_NE(what.find("not excited by the data: Fc6"), std::string::npos) << what;
    EXPECT_NE(what.find("not separable"), std::string::npos) << what;
    EXPECT_NE(what.find("XX2R"), std::string::npos) << what;
  }
}

TEST(Estimate, BadInputsAreErrors) {
  Eigen::MatrixXd W = Eigen::MatrixXd::Random(10, 2);
  Eigen::VectorXd y = Eigen::VectorXd::Random(10);
  EXPECT_THROW(fit_ols(W, Eigen::VectorXd::Zero(9), {"a", "b"}), EstimationError);
  EXPECT_THROW(fit_ols(W, y, {"a"}), EstimationError);
  EXPECT_THROW(fit_ols(W.topRows(2), y.head(2), {"a", "b"}), EstimationError);
  // A group number with no equations (here 1, between 0 and 2).
  std::vector<int> group(10, 0);
  for (int r = 5; r < 10; ++r) group[r] = 2;
  EXPECT_THROW(fit_wls(W, y, group, {"a", "b"}), EstimationError);
  EXPECT_THROW(essential_parameters(W, y, {}, {"a"}), EstimationError);
  W(3, 1) = std::nan("");
  EXPECT_THROW(fit_ols(W, y, {"a", "b"}), EstimationError);
}

// The statistics of eq. 15-20 from the normal equations in long double: an independent
// computation, accurate to ~1e-15 for the well-conditioned problems below.
using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
using LongVector = Eigen::Matrix<long double, Eigen::Dynamic, 1>;

struct Reference {
  Eigen::VectorXd value, std_dev;
  double residual_std_dev = 0, relative_error_norm = 0, condition_number = 0;
  std::vector<double> group_std_dev;
};

// Least squares of rows `rows` of W (all columns in `columns`) with weights w_r, in long double.
LongVector normal_solution(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                           const std::vector<Eigen::Index>& rows,
                           const std::vector<Eigen::Index>& columns,
                           const std::vector<long double>& weight, LongMatrix* inverse = nullptr) {
  const Eigen::Index b = static_cast<Eigen::Index>(columns.size());
  LongMatrix A = LongMatrix::Zero(b, b);
  LongVector rhs = LongVector::Zero(b);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Eigen::Index r = rows[i];
    const long double w2 = weight[i] * weight[i];
    for (Eigen::Index j = 0; j < b; ++j) {
      const long double a = W(r, columns[static_cast<std::size_t>(j)]);
      rhs[j] += w2 * a * static_cast<long double>(y[r]);
      for (Eigen::Index k = 0; k < b; ++k)
        A(j, k) += w2 * a * W(r, columns[static_cast<std::size_t>(k)]);
    }
  }
  const Eigen::LDLT<LongMatrix> ldlt(A);
  if (inverse != nullptr) *inverse = ldlt.solve(LongMatrix::Identity(b, b));
  return ldlt.solve(rhs);
}

// WLS as eq. 20 defines it (OLS when `group` is empty), from normal equations in long double.
Reference reference_fit(const Eigen::MatrixXd& W, const Eigen::VectorXd& y,
                        const std::vector<int>& group) {
  const Eigen::Index r = W.rows(), b = W.cols();
  std::vector<Eigen::Index> all_columns(static_cast<std::size_t>(b));
  for (Eigen::Index k = 0; k < b; ++k) all_columns[static_cast<std::size_t>(k)] = k;
  std::vector<long double> weight(static_cast<std::size_t>(r), 1.0L);
  Reference out;
  if (!group.empty()) {
    const int groups = *std::max_element(group.begin(), group.end()) + 1;
    for (int g = 0; g < groups; ++g) {
      std::vector<Eigen::Index> rows, seen;
      for (Eigen::Index i = 0; i < r; ++i) {
        if (group[static_cast<std::size_t>(i)] == g) rows.push_back(i);
      }
      for (Eigen::Index k = 0; k < b; ++k) {
        bool nonzero = false;
        for (Eigen::Index i : rows) nonzero = nonzero || W(i, k) != 0;
        if (nonzero) seen.push_back(k);
      }
      const LongVector x =
          normal_solution(W, y, rows, seen, std::vector<long double>(rows.size(), 1.0L));
      long double squares = 0;
      for (Eigen::Index i : rows) {
        long double e = y[i];
        for (std::size_t j = 0; j < seen.size(); ++j)
          e -= W(i, seen[j]) * x[static_cast<Eigen::Index>(j)];
        squares += e * e;
      }
      const long double sigma =
          std::sqrt(squares / static_cast<long double>(rows.size() - seen.size()));
      out.group_std_dev.push_back(static_cast<double>(sigma));
      for (Eigen::Index i : rows) weight[static_cast<std::size_t>(i)] = 1.0L / sigma;
    }
  }
  std::vector<Eigen::Index> all_rows(static_cast<std::size_t>(r));
  for (Eigen::Index i = 0; i < r; ++i) all_rows[static_cast<std::size_t>(i)] = i;
  LongMatrix inverse;
  const LongVector x = normal_solution(W, y, all_rows, all_columns, weight, &inverse);
  long double weighted = 0, plain = 0, y_squares = 0;
  for (Eigen::Index i = 0; i < r; ++i) {
    long double e = y[i];
    for (Eigen::Index k = 0; k < b; ++k) e -= W(i, k) * x[k];
    weighted += e * e * weight[static_cast<std::size_t>(i)] * weight[static_cast<std::size_t>(i)];
    plain += e * e;
    y_squares += static_cast<long double>(y[i]) * y[i];
  }
  const long double variance = weighted / static_cast<long double>(r - b);
  out.value = x.cast<double>();
  out.std_dev = (variance * inverse.diagonal()).cwiseSqrt().cast<double>();
  out.residual_std_dev = static_cast<double>(std::sqrt(variance));
  out.relative_error_norm = static_cast<double>(std::sqrt(plain / y_squares));
  // The condition number of the weighted W from its singular values, by SVD of W itself.
  Eigen::MatrixXd Ww = W;
  for (Eigen::Index i = 0; i < r; ++i)
    Ww.row(i) *= static_cast<double>(weight[static_cast<std::size_t>(i)]);
  const Eigen::VectorXd singular = Eigen::JacobiSVD<Eigen::MatrixXd>(Ww).singularValues();
  out.condition_number = singular[0] / singular[b - 1];
  return out;
}

void expect_matches(const LeastSquaresResult& fit, const Reference& reference, double tolerance,
                    const std::string& what) {
  EXPECT_LT(test::relative_error(fit.value, reference.value), tolerance) << what;
  EXPECT_LT(test::relative_error(fit.std_dev, reference.std_dev), tolerance) << what;
  EXPECT_NEAR(fit.residual_std_dev / reference.residual_std_dev, 1.0, tolerance) << what;
  EXPECT_NEAR(fit.relative_error_norm / reference.relative_error_norm, 1.0, tolerance) << what;
  EXPECT_NEAR(fit.condition_number / reference.condition_number, 1.0, 1e-9) << what;
  ASSERT_EQ(fit.group_std_dev.size(), reference.group_std_dev.size()) << what;
  for (std::size_t g = 0; g < fit.group_std_dev.size(); ++g) {
    EXPECT_NEAR(fit.group_std_dev[g] / reference.group_std_dev[g], 1.0, tolerance)
        << what << ", group " << g;
  }
  for (Eigen::Index k = 0; k < fit.value.size(); ++k) {
    EXPECT_NEAR(fit.rel_std_dev[k], 100.0 * fit.std_dev[k] / std::abs(fit.value[k]),
                1e-12 * fit.rel_std_dev[k]);
  }
}

// A random well-conditioned problem: 4 groups with their own noise levels, interleaved rows, a
// column that only groups 2 and 3 see (zero elsewhere) and one nonzero only late in group 1.
struct Problem {
  Eigen::MatrixXd W;
  Eigen::VectorXd y;
  std::vector<int> group;
  std::vector<std::string> names;
};

Problem random_problem(Eigen::Index rows, std::uint64_t seed) {
  test::Random random(seed);
  const int b = 6;
  Problem p;
  p.W.resize(rows, b);
  p.y.resize(rows);
  p.group.resize(static_cast<std::size_t>(rows));
  const Eigen::VectorXd beta = random.vector(b, -2, 2);
  const double noise[4] = {0.5, 0.05, 2.0, 0.2};
  for (Eigen::Index r = 0; r < rows; ++r) {
    const int g = static_cast<int>((r * 7 + r / 5) % 4);
    p.group[static_cast<std::size_t>(r)] = g;
    for (int k = 0; k < b; ++k) p.W(r, k) = random.uniform(-1, 1) + (k == 0 ? 1.5 : 0.0);
    if (g < 2) p.W(r, 4) = 0;                   // seen by groups 2 and 3 only
    if (g == 1 && r < rows / 2) p.W(r, 5) = 0;  // group 1 sees column 5 late
    p.y[r] = p.W.row(r).dot(beta) + noise[g] * gaussian(random);
  }
  p.names = {"a", "b", "c", "d", "e", "f"};
  return p;
}

TEST(Estimate, FitsMatchLongDoubleNormalEquations) {
  // 3000 rows: one thread; 50000 rows: the two halves in two threads, then merged.
  for (Eigen::Index rows : {Eigen::Index{3000}, Eigen::Index{50000}}) {
    const Problem p = random_problem(rows, 11);
    const std::string what = std::to_string(rows) + " rows";
    expect_matches(fit_ols(p.W, p.y, p.names), reference_fit(p.W, p.y, {}), 1e-10, "OLS, " + what);
    expect_matches(fit_wls(p.W, p.y, p.group, p.names), reference_fit(p.W, p.y, p.group), 1e-10,
                   "WLS, " + what);
  }
}

TEST(Estimate, AccumulatorFedInBlocksMatchesLongDoubleNormalEquations) {
  const Problem p = random_problem(7000, 12);
  const Eigen::Index b = p.W.cols();
  // Rows regrouped per group, row-major, fed in blocks of odd sizes to two accumulators (rows
  // alternate between them by block), then merged; column-major blocks to a third.
  std::vector<std::vector<Eigen::Index>> members(4);
  for (Eigen::Index r = 0; r < p.W.rows(); ++r)
    members[static_cast<std::size_t>(p.group[static_cast<std::size_t>(r)])].push_back(r);
  LeastSquaresAccumulator first(static_cast<int>(b), 4), second(static_cast<int>(b), 4),
      by_columns(static_cast<int>(b), 4);
  test::Random random(5);
  for (int g = 0; g < 4; ++g) {
    const std::vector<Eigen::Index>& m = members[static_cast<std::size_t>(g)];
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows_g(m.size(), b);
    Eigen::MatrixXd columns_g(m.size(), b);
    Eigen::VectorXd y_g(m.size());
    for (std::size_t i = 0; i < m.size(); ++i) {
      rows_g.row(static_cast<Eigen::Index>(i)) = p.W.row(m[i]);
      columns_g.row(static_cast<Eigen::Index>(i)) = p.W.row(m[i]);
      y_g[static_cast<Eigen::Index>(i)] = p.y[m[i]];
    }
    Eigen::Index start = 0;
    for (int block = 0; start < rows_g.rows(); ++block) {
      const Eigen::Index count = std::min<Eigen::Index>(
          rows_g.rows() - start, 1 + static_cast<Eigen::Index>(random.uniform(0, 700)));
      (block % 2 == 0 ? first : second)
          .add(g, count, rows_g.data() + start * b, b, 1, y_g.data() + start, 1);
      by_columns.add(g, count, columns_g.data() + start, 1, columns_g.rows(), y_g.data() + start,
                     1);
      start += count;
    }
  }
  first.merge(std::move(second));
  EXPECT_EQ(first.rows(), p.W.rows());
  EXPECT_EQ(second.rows(), 0);
  const Reference ols = reference_fit(p.W, p.y, {}), wls = reference_fit(p.W, p.y, p.group);
  for (const LeastSquaresAccumulator* a : {&first, &by_columns}) {
    const std::string what = a == &first ? "row-major blocks, merged" : "column-major blocks";
    expect_matches(a->fit_ols(p.names), ols, 1e-10, "OLS, " + what);
    expect_matches(a->fit_wls(p.names), wls, 1e-10, "WLS, " + what);
    // Each group's ||y_g|| and ||y_g - W_g beta||, against the residuals computed directly.
    for (int g = 0; g < 4; ++g) {
      double squares = 0, y_squares = 0;
      for (Eigen::Index r : members[static_cast<std::size_t>(g)]) {
        squares += std::pow(p.y[r] - p.W.row(r).dot(wls.value), 2);
        y_squares += p.y[r] * p.y[r];
      }
      EXPECT_NEAR(a->residual_norm(g, wls.value) / std::sqrt(squares), 1.0, 1e-10) << what;
      EXPECT_NEAR(a->y_norm(g) / std::sqrt(y_squares), 1.0, 1e-14) << what;
    }
  }
}

TEST(Estimate, WeightedLeastSquaresInClosedForm) {
  // y = beta x with one parameter: group 0 rows x = 1, 2, 3, 4, group 1 rows x = 1, 1, 1, 1, 1.
  // Group OLS: beta_g = sum(x y) / sum(x^2), sigma_g^2 = sum of squared errors / (n_g - 1);
  // then WLS: beta = sum(x y / sigma^2) / sum(x^2 / sigma^2), var = s^2 / sum(x^2 / sigma^2).
  const Eigen::VectorXd x{{1, 2, 3, 4, 1, 1, 1, 1, 1}};
  const Eigen::VectorXd y{{1.1, 1.9, 3.2, 3.9, 0.5, 1.5, 1.0, 0.8, 1.2}};
  const std::vector<int> group = {0, 0, 0, 0, 1, 1, 1, 1, 1};
  double sigma[2];
  for (int g = 0; g < 2; ++g) {
    double xy = 0, xx = 0, n = 0;
    for (int r = 0; r < 9; ++r) {
      if (group[static_cast<std::size_t>(r)] != g) continue;
      xy += x[r] * y[r];
      xx += x[r] * x[r];
      n += 1;
    }
    double squares = 0;
    for (int r = 0; r < 9; ++r) {
      if (group[static_cast<std::size_t>(r)] == g) squares += std::pow(y[r] - xy / xx * x[r], 2);
    }
    sigma[g] = std::sqrt(squares / (n - 1));
  }
  double xy = 0, xx = 0;
  for (int r = 0; r < 9; ++r) {
    const double w = 1.0 / sigma[group[static_cast<std::size_t>(r)]];
    xy += w * w * x[r] * y[r];
    xx += w * w * x[r] * x[r];
  }
  const double beta = xy / xx;
  double weighted_squares = 0;
  for (int r = 0; r < 9; ++r) {
    weighted_squares +=
        std::pow((y[r] - beta * x[r]) / sigma[group[static_cast<std::size_t>(r)]], 2);
  }
  const double s2 = weighted_squares / 8;
  const LeastSquaresResult fit = fit_wls(x, y, group, {"Fv1"});
  EXPECT_NEAR(fit.value[0], beta, 1e-14);
  EXPECT_NEAR(fit.group_std_dev[0], sigma[0], 1e-14);
  EXPECT_NEAR(fit.group_std_dev[1], sigma[1], 1e-14);
  EXPECT_NEAR(fit.residual_std_dev, std::sqrt(s2), 1e-14);
  EXPECT_NEAR(fit.std_dev[0], std::sqrt(s2 / xx), 1e-14);
  EXPECT_NEAR(fit.rel_std_dev[0], 100 * std::sqrt(s2 / xx) / beta, 1e-12);
  EXPECT_DOUBLE_EQ(fit.condition_number, 1.0);
  ASSERT_EQ(fit.information.rows(), 1);
  EXPECT_NEAR(fit.information(0, 0), xx / s2, 1e-12 * xx / s2);
}

TEST(Estimate, InformationIsTheNormalMatrixOverTheVariance) {
  // Several columns, a column order the pivoting QR will permute: W'W / s^2 formed directly.
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0, 1);
  Eigen::MatrixXd W(200, 4);
  for (Eigen::Index i = 0; i < W.size(); ++i) W.data()[i] = normal(rng);
  W.col(0) *= 1e-3;
  W.col(3) *= 50;
  Eigen::VectorXd y = W * Eigen::Vector4d(1, -2, 3, 0.5);
  for (Eigen::Index r = 0; r < y.size(); ++r) y[r] += 0.1 * normal(rng);
  const LeastSquaresResult fit = fit_ols(W, y, {"a", "b", "c", "d"});
  const double s2 = (y - W * fit.value).squaredNorm() / (200 - 4);
  const Eigen::MatrixXd expected = W.transpose() * W / s2;
  EXPECT_LT((fit.information - expected).norm(), 1e-10 * expected.norm());
}

TEST(Estimate, NonFiniteValuesAreNamed) {
  Problem p = random_problem(300, 13);
  p.W(41, 4) = std::nan("");  // row 42, in a group (1) that otherwise never sees column 'e'
  try {
    fit_wls(p.W, p.y, p.group, p.names);
    ADD_FAILURE() << "NaN accepted";
  } catch (const EstimationError& e) {
    EXPECT_NE(std::string(e.what()).find("W row 42, column 'e' is nan"), std::string::npos)
        << e.what();
  }
  p.W(41, 4) = 0;
  p.y[7] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(fit_ols(p.W, p.y, p.names), EstimationError);
  LeastSquaresAccumulator equations(6, 4);
  equations.add(2, 300, p.W.data(), 1, 300, p.y.data(), 1);
  try {
    equations.fit_ols(p.names);
    ADD_FAILURE() << "infinity accepted";
  } catch (const EstimationError& e) {
    EXPECT_NE(std::string(e.what()).find("NaN or infinite values (in group 2)"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(equations.add(4, 1, p.W.data(), 1, 300, p.y.data(), 1), EstimationError);
  EXPECT_THROW(LeastSquaresAccumulator(0, 1), EstimationError);
  LeastSquaresAccumulator other(5, 4);
  EXPECT_THROW(equations.merge(std::move(other)), EstimationError);
}

TEST(Estimate, AccumulatorWlsNeedsEveryGroup) {
  const Problem p = random_problem(400, 14);
  LeastSquaresAccumulator equations(6, 5);  // group 4 gets no equations
  for (Eigen::Index r = 0; r < p.W.rows(); ++r) {
    equations.add(p.group[static_cast<std::size_t>(r)], 1, &p.W(r, 0), 0, p.W.rows(), &p.y[r], 0);
  }
  EXPECT_NO_THROW(equations.fit_ols(p.names));
  try {
    equations.fit_wls(p.names);
    ADD_FAILURE() << "empty group accepted";
  } catch (const EstimationError& e) {
    EXPECT_NE(std::string(e.what()).find("group 4 has no equations"), std::string::npos)
        << e.what();
  }
}

TEST_F(SimulatedTx40, EssentialParametersFromTheAccumulatorAgree) {
  test::Random random(78);
  Eigen::VectorXd y = data_->tau;
  for (Eigen::Index r = 0; r < y.size(); ++r) y[r] += kNoise[data_->group[r]] * gaussian(random);
  const EssentialParameters whole =
      essential_parameters(data_->W, y, data_->group, data_->names, 20.0);
  const int b = static_cast<int>(data_->W.cols());
  LeastSquaresAccumulator equations(b, 6);
  for (Eigen::Index r = 0; r < y.size(); ++r) {
    equations.add(data_->group[static_cast<std::size_t>(r)], 1, &data_->W(r, 0), 0, data_->W.rows(),
                  &y[r], 0);
  }
  const EssentialParameters streamed = essential_parameters(equations, true, data_->names, 20.0);
  EXPECT_EQ(streamed.kept, whole.kept);
  EXPECT_EQ(streamed.eliminated, whole.eliminated);
  EXPECT_LT(test::relative_error(streamed.fit.value, whole.fit.value), 1e-10);
  // The essential fit is the WLS of W restricted to the kept columns.
  Eigen::MatrixXd W_kept(data_->W.rows(), static_cast<Eigen::Index>(whole.kept.size()));
  std::vector<std::string> kept_names;
  for (std::size_t i = 0; i < whole.kept.size(); ++i) {
    W_kept.col(static_cast<Eigen::Index>(i)) = data_->W.col(whole.kept[i]);
    kept_names.push_back(data_->names[static_cast<std::size_t>(whole.kept[i])]);
  }
  const LeastSquaresResult direct = fit_wls(W_kept, y, data_->group, kept_names);
  EXPECT_LT(test::relative_error(whole.fit.value, direct.value), 1e-10);
  EXPECT_LT(test::relative_error(whole.fit.std_dev, direct.std_dev), 1e-10);
}

}  // namespace
}  // namespace modelgen
