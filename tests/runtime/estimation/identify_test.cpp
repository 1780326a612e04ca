// identify() on the TX-40's checked-in generated model (Gautier & Briot eq. 14-20): two
// simulated Fourier experiments (Swevers eq. 15-17), enough samples for the two-thread path with
// the split inside an experiment. Noise-free torques must give the base parameters exactly with
// every method; with noise, the estimate and its statistics must equal WLS computed here
// independently (stacked W, normal equations in long double) and the torque errors the residuals
// computed directly. Also progress reports, cancellation, and errors naming the bad sample.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>

#include "generated/tx40/tx40.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/estimation_error.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
using LongVector = Eigen::Matrix<long double, Eigen::Dynamic, 1>;

constexpr double kNoise[6] = {2.0, 2.0, 1.0, 0.3, 0.3, 0.1};  // N m per joint

double gaussian(test::Random& random) {
  const double u = random.uniform(1e-300, 1.0), v = random.uniform(0.0, 1.0);
  return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * v);
}

class Tx40Identification : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    const modelgen::RobotModel description =
        modelgen::load_robot(test::source_path("robots/tx40.yaml"));
    test::Random random(31);
    const Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
    beta_ = new Eigen::VectorXd(model_.num_base_params());
    model_.base_from_standard(p.data(), beta_->data());
    exact_ = new std::vector<Trajectory>();
    // 2500 + 3500 samples: the halves meet inside the second experiment.
    for (const Eigen::Index samples : {Eigen::Index{2500}, Eigen::Index{3500}}) {
      FourierTrajectory fourier;
      fourier.period = 10.0;
      fourier.q0 = random.vector(6, -0.5, 0.5);
      fourier.a.resize(6, 5);
      fourier.b.resize(6, 5);
      for (Eigen::Index j = 0; j < 6; ++j) {
        for (Eigen::Index l = 0; l < 5; ++l) {
          fourier.a(j, l) = random.uniform(-0.5, 0.5);
          fourier.b(j, l) = random.uniform(-0.5, 0.5);
        }
      }
      Trajectory x = sample(fourier, fourier.period / static_cast<double>(samples), fourier.period);
      x.source = "experiment" + std::to_string(exact_->size() + 1) + ".csv";
      for (Eigen::Index s = 0; s < x.t.size(); ++s) {
        const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
        Eigen::VectorXd tau(6);
        tx40::inverse_dynamics(q.data(), dq.data(), ddq.data(), beta_->data(), tau.data());
        x.tau.row(s) = tau;
      }
      exact_->push_back(std::move(x));
    }
    noisy_ = new std::vector<Trajectory>(*exact_);
    for (Trajectory& x : *noisy_) {
      for (Eigen::Index s = 0; s < x.t.size(); ++s) {
        for (int j = 0; j < 6; ++j) x.tau(s, j) += kNoise[j] * gaussian(random);
      }
    }
  }
  static void TearDownTestSuite() {
    delete beta_;
    delete exact_;
    delete noisy_;
  }

  static const GeneratedModel<tx40::Model> model_;
  static Eigen::VectorXd* beta_;
  static std::vector<Trajectory>* exact_;
  static std::vector<Trajectory>* noisy_;
};

const GeneratedModel<tx40::Model> Tx40Identification::model_;
Eigen::VectorXd* Tx40Identification::beta_ = nullptr;
std::vector<Trajectory>* Tx40Identification::exact_ = nullptr;
std::vector<Trajectory>* Tx40Identification::noisy_ = nullptr;

TEST_F(Tx40Identification, NoiseFreeTorquesGiveTheExactParametersWithEveryMethod) {
  for (const Method method : {Method::kOls, Method::kWls, Method::kPimWls}) {
    const Identification id = identify(model_, *exact_, method);
    const std::string what = method == Method::kOls   ? "ols"
                             : method == Method::kWls ? "wls"
                                                      : "pim-wls";
    EXPECT_LT(test::relative_error(id.fit.value, *beta_), 1e-8) << what;
    EXPECT_LT(id.torque_rel_error_norm, 1e-10) << what;
    EXPECT_LT(id.rms_error.maxCoeff(), 1e-10 * id.rms_torque.maxCoeff()) << what;
    EXPECT_EQ(id.samples, 6000);
    EXPECT_EQ(id.names, model_.base_param_names());
  }
}

// The stacked IDIM of the noisy data and WLS with one group per joint and experiment (eq. 20),
// from normal equations in long double: group sigmas on the columns each group sees, then the
// weighted solution and its standard deviations.
struct Independent {
  Eigen::VectorXd value, std_dev, rms_error, rms_torque;
  std::vector<double> group_std_dev;
  double torque_rel_error_norm = 0;
};

Independent independent_wls(const std::vector<Trajectory>& data) {
  const int n = tx40::kDof, nb = tx40::kBaseParams;
  std::vector<std::vector<double>> rows;  // W rows with tau last, per group
  std::vector<int> group;
  for (std::size_t e = 0; e < data.size(); ++e) {
    const Trajectory& x = data[e];
    std::vector<double> W(static_cast<std::size_t>(n * nb));
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
      tx40::idim_regressor(q.data(), dq.data(), ddq.data(), W.data());
      for (int j = 0; j < n; ++j) {
        std::vector<double> row(W.begin() + j * nb, W.begin() + (j + 1) * nb);
        row.push_back(x.tau(s, j));
        rows.push_back(std::move(row));
        group.push_back(static_cast<int>(e) * n + j);
      }
    }
  }
  const int groups = static_cast<int>(data.size()) * n;
  // Normal equations over the rows of one group (or all, g < 0) restricted to `columns`.
  const auto solve = [&](int g, const std::vector<int>& columns, const std::vector<long double>& w,
                         LongMatrix* inverse) {
    const Eigen::Index c = static_cast<Eigen::Index>(columns.size());
    LongMatrix A = LongMatrix::Zero(c, c);
    LongVector b = LongVector::Zero(c);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (g >= 0 && group[r] != g) continue;
      const long double w2 =
          w[static_cast<std::size_t>(group[r])] * w[static_cast<std::size_t>(group[r])];
      for (Eigen::Index i = 0; i < c; ++i) {
        const long double a =
            rows[r][static_cast<std::size_t>(columns[static_cast<std::size_t>(i)])];
        b[i] += w2 * a * rows[r][static_cast<std::size_t>(nb)];
        for (Eigen::Index k = 0; k < c; ++k) {
          A(i, k) +=
              w2 * a * rows[r][static_cast<std::size_t>(columns[static_cast<std::size_t>(k)])];
        }
      }
    }
    const Eigen::LDLT<LongMatrix> ldlt(A);
    if (inverse != nullptr) *inverse = ldlt.solve(LongMatrix::Identity(c, c));
    return LongVector(ldlt.solve(b));
  };
  const auto residual = [&](std::size_t r, const std::vector<int>& columns, const LongVector& x) {
    long double e = rows[r][static_cast<std::size_t>(nb)];
    for (std::size_t i = 0; i < columns.size(); ++i) {
      e -= rows[r][static_cast<std::size_t>(columns[i])] * x[static_cast<Eigen::Index>(i)];
    }
    return e;
  };
  Independent out;
  std::vector<long double> weight(static_cast<std::size_t>(groups), 1.0L);
  for (int g = 0; g < groups; ++g) {
    // The columns the group sees. Some are zero in exact arithmetic but not in floating point
    // (joint 1's rows of ZZ2R and ZZ3R hold ~1e-17: the generated expression is a cancelling
    // difference); the fit's rank-revealing QR leaves them out, so does this computation.
    std::vector<long double> norm(static_cast<std::size_t>(nb), 0.0L);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (group[r] != g) continue;
      for (int k = 0; k < nb; ++k) {
        norm[static_cast<std::size_t>(k)] +=
            rows[r][static_cast<std::size_t>(k)] * rows[r][static_cast<std::size_t>(k)];
      }
    }
    const long double largest = *std::max_element(norm.begin(), norm.end());
    std::vector<int> seen;
    for (int k = 0; k < nb; ++k) {
      if (norm[static_cast<std::size_t>(k)] > 1e-24L * largest) seen.push_back(k);
    }
    const LongVector x =
        solve(g, seen, std::vector<long double>(static_cast<std::size_t>(groups), 1.0L), nullptr);
    long double squares = 0, count = 0;
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (group[r] != g) continue;
      squares += residual(r, seen, x) * residual(r, seen, x);
      count += 1;
    }
    const long double sigma = std::sqrt(squares / (count - static_cast<long double>(seen.size())));
    out.group_std_dev.push_back(static_cast<double>(sigma));
    weight[static_cast<std::size_t>(g)] = 1.0L / sigma;
  }
  std::vector<int> all(static_cast<std::size_t>(nb));
  for (int k = 0; k < nb; ++k) all[static_cast<std::size_t>(k)] = k;
  LongMatrix inverse;
  const LongVector x = solve(-1, all, weight, &inverse);
  long double weighted = 0, plain = 0, tau_squares = 0;
  LongVector joint_error = LongVector::Zero(n), joint_tau = LongVector::Zero(n);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const long double e = residual(r, all, x), w = weight[static_cast<std::size_t>(group[r])];
    const long double tau = rows[r][static_cast<std::size_t>(nb)];
    weighted += e * e * w * w;
    plain += e * e;
    tau_squares += tau * tau;
    joint_error[group[r] % n] += e * e;
    joint_tau[group[r] % n] += tau * tau;
  }
  const long double samples = static_cast<long double>(rows.size() / n);
  const long double variance = weighted / static_cast<long double>(rows.size() - nb);
  out.value = x.cast<double>();
  out.std_dev = (variance * inverse.diagonal()).cwiseSqrt().cast<double>();
  out.torque_rel_error_norm = static_cast<double>(std::sqrt(plain / tau_squares));
  out.rms_error = (joint_error / samples).cwiseSqrt().cast<double>();
  out.rms_torque = (joint_tau / samples).cwiseSqrt().cast<double>();
  return out;
}

TEST_F(Tx40Identification, NoisyWlsEqualsAnIndependentComputation) {
  const Identification id = identify(model_, *noisy_, Method::kWls);
  const Independent expected = independent_wls(*noisy_);
  EXPECT_LT(test::relative_error(id.fit.value, expected.value), 1e-10);
  EXPECT_LT(test::relative_error(id.fit.std_dev, expected.std_dev), 1e-10);
  ASSERT_EQ(id.fit.group_std_dev.size(), 12u);
  for (std::size_t g = 0; g < 12; ++g) {
    EXPECT_NEAR(id.fit.group_std_dev[g] / expected.group_std_dev[g], 1.0, 1e-10) << "group " << g;
    // Eq. 20 recovers each joint's noise level.
    EXPECT_NEAR(id.fit.group_std_dev[g] / kNoise[g % 6], 1.0, 0.15) << "group " << g;
  }
  EXPECT_LT(test::relative_error(id.rms_error, expected.rms_error), 1e-10);
  EXPECT_LT(test::relative_error(id.rms_torque, expected.rms_torque), 1e-12);
  EXPECT_NEAR(id.torque_rel_error_norm / expected.torque_rel_error_norm, 1.0, 1e-10);
}

TEST_F(Tx40Identification, PimTorqueErrorsAreTheDirectResiduals) {
  const Identification id = identify(model_, *noisy_, Method::kPimWls);
  ASSERT_EQ(id.fit.group_std_dev.size(), 2u);  // one group per experiment
  // Measured minus predicted torques from the regressor and the estimate, computed here.
  Eigen::VectorXd error = Eigen::VectorXd::Zero(6), torque = Eigen::VectorXd::Zero(6);
  std::vector<double> W(6 * tx40::kBaseParams);
  for (const Trajectory& x : *noisy_) {
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
      tx40::idim_regressor(q.data(), dq.data(), ddq.data(), W.data());
      const Eigen::Map<const Eigen::Matrix<double, 6, tx40::kBaseParams, Eigen::RowMajor>> Wm(
          W.data());
      const Eigen::VectorXd e = x.tau.row(s).transpose() - Wm * id.fit.value;
      error += e.cwiseAbs2();
      torque += x.tau.row(s).transpose().cwiseAbs2();
    }
  }
  EXPECT_LT(test::relative_error(id.rms_error, (error / 6000.0).cwiseSqrt()), 1e-9);
  EXPECT_LT(test::relative_error(id.rms_torque, (torque / 6000.0).cwiseSqrt()), 1e-12);
  EXPECT_NEAR(id.torque_rel_error_norm, std::sqrt(error.sum() / torque.sum()), 1e-9);
}

TEST_F(Tx40Identification, ProgressIsReportedAndCancels) {
  std::vector<double> reports;
  identify(model_, *noisy_, Method::kPimWls, [&](double f) { reports.push_back(f); });
  ASSERT_GE(reports.size(), 10u);
  EXPECT_LE(reports.size(), 101u);
  EXPECT_TRUE(std::is_sorted(reports.begin(), reports.end()));
  EXPECT_EQ(reports.front(), 0.0);
  EXPECT_EQ(reports.back(), 1.0);
  // An exception from the callback stops both threads and reaches the caller.
  int calls = 0;
  EXPECT_THROW(identify(model_, *noisy_, Method::kWls,
                        [&](double f) {
                          ++calls;
                          if (f > 0.2) throw std::runtime_error("cancelled");
                        }),
               std::runtime_error);
  EXPECT_LT(calls, 40);
}

TEST_F(Tx40Identification, BadDataIsNamed) {
  std::vector<Trajectory> data = *exact_;
  data[1].ddq(6, 1) = std::nan("");
  try {
    identify(model_, data, Method::kWls);
    ADD_FAILURE() << "NaN accepted";
  } catch (const EstimationError& e) {
    EXPECT_STREQ(e.what(),
                 "experiment2.csv: sample 7: 'ddq2' is nan; measured data must be finite");
  }
  data = *exact_;
  data[0].tau.conservativeResize(100, 6);
  EXPECT_THROW(identify(model_, data, Method::kOls), EstimationError);
  EXPECT_THROW(identify(model_, {}, Method::kOls), EstimationError);
  // 8 samples (48 torque equations) cannot determine 61 parameters.
  data = {exact_->front()};
  for (Eigen::MatrixXd* a : {&data[0].q, &data[0].dq, &data[0].ddq, &data[0].tau}) {
    a->conservativeResize(8, 6);
  }
  data[0].t.conservativeResize(8);
  try {
    identify(model_, data, Method::kOls);
    ADD_FAILURE() << "8 samples accepted";
  } catch (const EstimationError& e) {
    EXPECT_NE(std::string(e.what()).find("48 equations for 61 parameters"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace modelgen
