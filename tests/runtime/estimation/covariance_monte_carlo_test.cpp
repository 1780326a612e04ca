// Issue 31, "standard deviations that hold": IDIM-WLS on the TX-40 (open loop), repeated over
// independent noise, must report standard deviations that match the spread of its estimates
// (tests/support/monte_carlo_spread.hpp). The data are made here: states from a Fourier
// trajectory (Swevers eq. 15-17), torques from the generated inverse dynamics at random
// physical parameters, and torque noise that is
//   - white (the plain s^2 (W^T W)^-1 of Gautier & Briot eq. 17-18 holds);
//   - averaged over periods and cut at a harmonic (the periodic route): the noise left lives on
//     2 H + 1 lines per joint, not on N samples, so eq. 17 underestimates it;
//   - an AR(1) process filtered and decimated by identify() (eq. 13-14): the decimated rows
//     keep a correlation from row to row;
//   - the same AR(1) process on undecimated rows (a record already at a low rate, or
//     --decimate 1): eq. 18 would report sqrt((1 - rho) / (1 + rho)) = 0.16 of the spread;
//     and the power equations (PIM, eq. 9-10) of that record.
// 200 runs (100 for the AR(1) cases, 10 000 samples each): the spread's relative error is
// then 1 / sqrt(398) = 5 % (7 %).

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "generated/tx40/tx40.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/monte_carlo_spread.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

constexpr double kNoise[6] = {2.0, 2.0, 1.0, 0.3, 0.3, 0.1};  // N m per joint
constexpr int kRuns = 200;

class CovarianceMonteCarlo : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    const RobotModel description = load_robot(test::source_path("robots/tx40.yaml"));
    test::Random random(31);
    const Eigen::VectorXd p = test::random_physical_parameters(description.tree, random);
    beta_ = Eigen::VectorXd(model_.num_base_params());
    model_.base_from_standard(p.data(), beta_.data());
    fourier_.period = 10.0;
    fourier_.q0 = random.vector(6, -0.5, 0.5);
    fourier_.a.resize(6, 5);
    fourier_.b.resize(6, 5);
    for (Eigen::Index j = 0; j < 6; ++j) {
      for (Eigen::Index l = 0; l < 5; ++l) {
        fourier_.a(j, l) = random.uniform(-0.5, 0.5);
        fourier_.b(j, l) = random.uniform(-0.5, 0.5);
      }
    }
  }

  // The trajectory sampled with `samples` per period over `periods`, exact torques.
  static Trajectory exact(Eigen::Index samples, int periods) {
    Trajectory x =
        sample(fourier_, fourier_.period / static_cast<double>(samples), fourier_.period * periods);
    x.source = "simulated";
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      const Eigen::VectorXd q = x.q.row(s), dq = x.dq.row(s), ddq = x.ddq.row(s);
      Eigen::VectorXd tau(6);
      tx40::inverse_dynamics(q.data(), dq.data(), ddq.data(), beta_.data(), tau.data());
      x.tau.row(s) = tau;
    }
    return x;
  }

  // AR(1) torque noise on undecimated rows, fitted by `method`, against its spread.
  static void undecimated_ar1(Method method, unsigned seed);

  static const GeneratedModel<tx40::Model> model_;
  static Eigen::VectorXd beta_;
  static FourierTrajectory fourier_;
};

const GeneratedModel<tx40::Model> CovarianceMonteCarlo::model_;
Eigen::VectorXd CovarianceMonteCarlo::beta_;
FourierTrajectory CovarianceMonteCarlo::fourier_;

// Column by column, the harmonics 0..H of a period of N samples (a direct real DFT).
Eigen::MatrixXd keep_harmonics(const Eigen::MatrixXd& x, int H) {
  const Eigen::Index N = x.rows();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(N, x.cols());
  for (int l = 0; l <= H; ++l) {
    Eigen::VectorXd c(N), s(N);
    for (Eigen::Index k = 0; k < N; ++k) {
      const double angle = 2 * std::numbers::pi * l * static_cast<double>(k) / N;
      c[k] = std::cos(angle);
      s[k] = std::sin(angle);
    }
    const double scale = (l == 0 ? 1.0 : 2.0) / static_cast<double>(N);
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      out.col(j) += scale * (c.dot(x.col(j)) * c + s.dot(x.col(j)) * s);
    }
  }
  return out;
}

TEST_F(CovarianceMonteCarlo, WhiteNoise) {
  const Trajectory clean = exact(2000, 1);
  test::Random random(1);
  test::SpreadCheck check(beta_.size());
  for (int run = 0; run < kRuns; ++run) {
    Trajectory x = clean;
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      for (int j = 0; j < 6; ++j) x.tau(s, j) += kNoise[j] * random.normal();
    }
    const Identification id = identify(model_, {x}, Method::kWls);
    check.add(id.fit.value, id.fit.std_dev);
  }
  check.expect_covered("IDIM-WLS, white noise");
}

// Five periods averaged, the torque noise kept up to harmonic 40, positions exact. Only the noise
// is cut: the TX-40's Coulomb friction puts torque on every harmonic, and a cut there would add
// the same model error to every run, which is not what this test is about.
TEST_F(CovarianceMonteCarlo, PeriodicTorquesCutAtHarmonic) {
  constexpr int kPeriods = 5, kHarmonics = 40;
  constexpr Eigen::Index kSamples = 400;
  const Trajectory period = exact(kSamples, 1);
  test::Random random(2);
  test::SpreadCheck check(beta_.size());
  IdentifyOptions options;
  options.torque_harmonics = {kHarmonics};
  for (int run = 0; run < kRuns; ++run) {
    Eigen::MatrixXd noise = Eigen::MatrixXd::Zero(kSamples, 6);
    for (int p = 0; p < kPeriods; ++p) {
      for (Eigen::Index s = 0; s < kSamples; ++s) {
        for (int j = 0; j < 6; ++j) noise(s, j) += kNoise[j] * random.normal() / kPeriods;
      }
    }
    Trajectory x = period;
    x.tau = period.tau + keep_harmonics(noise, kHarmonics);
    const Identification id = identify(model_, {x}, Method::kWls, options);
    check.add(id.fit.value, id.fit.std_dev);
  }
  check.expect_covered("IDIM-WLS, periodic, torques cut at harmonic 40");
}

// 1 kHz samples, torque noise AR(1) with a 20-sample correlation (the stationary sd kNoise),
// decimated by 10: the decimated noise keeps a correlation of about 0.95^10 = 0.6 per row.
TEST_F(CovarianceMonteCarlo, CorrelatedNoiseDecimated) {
  constexpr double kRho = 0.95;
  const Trajectory clean = exact(10000, 1);
  test::Random random(3);
  test::SpreadCheck check(beta_.size());
  IdentifyOptions options;
  options.decimation = {10};
  for (int run = 0; run < kRuns / 2; ++run) {
    Trajectory x = clean;
    Eigen::VectorXd e(6);
    for (int j = 0; j < 6; ++j) e[j] = kNoise[j] * random.normal();
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      for (int j = 0; j < 6; ++j) {
        e[j] = kRho * e[j] + std::sqrt(1 - kRho * kRho) * kNoise[j] * random.normal();
        x.tau(s, j) += e[j];
      }
    }
    const Identification id = identify(model_, {x}, Method::kWls, options);
    check.add(id.fit.value, id.fit.std_dev);
  }
  check.expect_covered("IDIM-WLS, AR(1) noise, decimated by 10");
}

// The undecimated rows of the same AR(1) noise: the residuals are streamed, their scores
// prewhitened by the residuals' AR(1) coefficient and summed by batch means (Andrews & Monahan
// 1992). Summed raw, with Andrews' bandwidth of the raw residuals (about 180 rows), the sd were
// 0.84 (IDIM) and 0.74 (PIM) of the spread: that window in frequency holds few lines, and the fit
// had taken the noise out of many of them (its slow columns).
void CovarianceMonteCarlo::undecimated_ar1(Method method, unsigned seed) {
  constexpr double kRho = 0.95;
  const Trajectory clean = exact(10000, 1);
  test::Random random(seed);
  test::SpreadCheck check(beta_.size());
  for (int run = 0; run < kRuns / 2; ++run) {
    Trajectory x = clean;
    Eigen::VectorXd e(6);
    for (int j = 0; j < 6; ++j) e[j] = kNoise[j] * random.normal();
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      for (int j = 0; j < 6; ++j) {
        e[j] = kRho * e[j] + std::sqrt(1 - kRho * kRho) * kNoise[j] * random.normal();
        x.tau(s, j) += e[j];
      }
    }
    const Identification id = identify(model_, {x}, method);
    EXPECT_NE(id.fit.covariance.find("undecimated"), std::string::npos) << id.fit.covariance;
    check.add(id.fit.value, id.fit.std_dev);
  }
  check.expect_covered(method == Method::kWls ? "IDIM-WLS, AR(1) noise, undecimated"
                                              : "PIM-WLS, AR(1) noise, undecimated");
}

TEST_F(CovarianceMonteCarlo, CorrelatedNoiseUndecimated) { undecimated_ar1(Method::kWls, 4); }

// The power equations (eq. 9-10) of the same record: the noise dq . e keeps e's correlation.
TEST_F(CovarianceMonteCarlo, PowerEquationsCorrelatedNoiseUndecimated) {
  undecimated_ar1(Method::kPimWls, 5);
}

}  // namespace
}  // namespace modelgen
