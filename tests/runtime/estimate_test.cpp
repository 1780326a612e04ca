// Least squares with statistics (Gautier & Briot eq. 15-20) on simulated TX-40 data: the base
// regressor of the numeric reference along Fourier trajectories, torques from known physical
// parameters plus Gaussian noise of known level per joint. Noise-free data must give the
// parameters exactly; with noise the standard deviations must describe the actual errors.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "generator/description/load_robot.hpp"
#include "modelgen/base_parameters.hpp"
#include "modelgen/estimate.hpp"
#include "modelgen/reference_dynamics.hpp"
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
    const gen::RobotModel model = gen::load_robot(test::source_path("robots/tx40.yaml"));
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
    const LeastSquaresResult fit = weighted ? fit_wls(data_->W, data_->tau, data_->group, data_->names)
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

}  // namespace
}  // namespace modelgen
