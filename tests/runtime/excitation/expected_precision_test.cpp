// The expected standard deviations modelid design reports (expected_std_devs, sigma^2
// (W^T W)^-1 over one period of the design) against a Monte-Carlo: the bundled TX-40 design
// (robots/data/tx40/design.yaml) sampled at the instants the prediction used, torques from a
// true parameter vector through the generated model's inverse dynamics, fresh Gaussian noise
// of known sigma per run, each run fitted with identify()'s IDIM-WLS (Gautier & Briot eq. 20).
// The rms deviation of the estimates from the truth must equal the predicted std within 20 %
// for every base parameter.

#include "modelgen/excitation/expected_precision.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "generated/tx40/tx40.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/excitation/excitation_design.hpp"
#include "modelgen/model/identification_model.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

// The position-form series of a file modelid design wrote, read here with yaml-cpp.
FourierTrajectory read_design(const std::string& path) {
  const YAML::Node root = YAML::LoadFile(path);
  const YAML::Node joints = root["joints"];
  const auto dof = static_cast<Eigen::Index>(joints.size());
  const auto harmonics = static_cast<Eigen::Index>(joints[0]["a"].size());
  Eigen::VectorXd q0(dof);
  Eigen::MatrixXd a(dof, harmonics), b(dof, harmonics);
  for (Eigen::Index j = 0; j < dof; ++j) {
    const YAML::Node joint = joints[static_cast<std::size_t>(j)];
    q0[j] = joint["q0"].as<double>();
    for (Eigen::Index l = 0; l < harmonics; ++l) {
      a(j, l) = joint["a"][static_cast<std::size_t>(l)].as<double>();
      b(j, l) = joint["b"][static_cast<std::size_t>(l)].as<double>();
    }
  }
  return to_trajectory(q0, a, b, root["period"].as<double>());
}

TEST(ExpectedPrecision, AgreesWithTheSpreadOfWlsFitsOfNoisyRuns) {
  const GeneratedModel<tx40::Model> model;
  const FourierTrajectory design = read_design(test::source_path("robots/data/tx40/design.yaml"));
  // modelid design's default for 5 harmonics: 200 samples per period (20 Hz over 10 s).
  constexpr int kSamples = 200;
  constexpr double kNoise = 0.5;  // N m on every torque sample
  // Runs: the rms of n estimates about the truth is sd sqrt(chi2_n / n), whose relative
  // spread is 1 / sqrt(2 n): 10 % for the 50 runs, so a 20 % band would be only two
  // sigma and about 5 % of the 60 parameters would leave it by chance. 400 runs make the band
  // 5.7 sigma (P < 1e-6 per parameter under chi-square with 400 degrees of freedom) at
  // ~1.5 ms a fit.
  constexpr int kRuns = 400;

  const Eigen::MatrixXd W = stacked_regressor(model, design, kSamples);
  const Eigen::VectorXd predicted = expected_std_devs(W, kNoise);

  // The truth: any vector does (the fit is linear, its scatter independent of the truth);
  // torque magnitudes of a robot arm keep the WLS weights in a realistic range.
  test::Random random(12);
  const int nb = model.num_base_params();
  const Eigen::VectorXd truth = random.vector(nb, -1.0, 1.0);
  Trajectory clean = sample(design, design.period / kSamples, design.period);
  ASSERT_EQ(clean.t.size(), kSamples);
  for (Eigen::Index s = 0; s < clean.t.size(); ++s) {
    const Eigen::VectorXd q = clean.q.row(s), dq = clean.dq.row(s), ddq = clean.ddq.row(s);
    Eigen::VectorXd tau(model.dof());
    model.inverse_dynamics(q.data(), dq.data(), ddq.data(), truth.data(), tau.data());
    clean.tau.row(s) = tau;
  }
  Eigen::VectorXd squared_error = Eigen::VectorXd::Zero(nb);
  for (int run = 0; run < kRuns; ++run) {
    Trajectory noisy = clean;
    for (Eigen::Index s = 0; s < noisy.tau.rows(); ++s) {
      for (Eigen::Index j = 0; j < noisy.tau.cols(); ++j) noisy.tau(s, j) += kNoise * random.normal();
    }
    const Identification id = identify(model, {noisy}, Method::kWls);
    squared_error += (id.fit.value - truth).cwiseAbs2();
  }
  const Eigen::VectorXd spread = (squared_error / kRuns).cwiseSqrt();
  double lowest = INFINITY, highest = 0;
  for (int k = 0; k < nb; ++k) {
    const double ratio = spread[k] / predicted[k];
    lowest = std::min(lowest, ratio), highest = std::max(highest, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.2) << model.base_param_names()[static_cast<std::size_t>(k)]
                                 << ": Monte-Carlo sd " << spread[k] << ", predicted "
                                 << predicted[k];
  }
  std::cout << "[ summary  ] " << kRuns << " WLS fits of the TX-40 design, " << nb
            << " base parameters: Monte-Carlo sd / predicted sd from " << lowest << " to "
            << highest << "\n";
}

TEST(ExpectedPrecision, IsSigmaTimesTheRootOfTheInverseInformationDiagonal) {
  // A 3 x 2 example by hand: W^T W = [[2, 1], [1, 2]], inverse [[2, -1], [-1, 2]] / 3.
  Eigen::MatrixXd W(3, 2);
  W << 1, 0, 0, 1, 1, 1;
  const Eigen::VectorXd sd = expected_std_devs(W, 3.0);
  EXPECT_NEAR(sd[0], 3.0 * std::sqrt(2.0 / 3.0), 1e-12);
  EXPECT_NEAR(sd[1], 3.0 * std::sqrt(2.0 / 3.0), 1e-12);
  Eigen::MatrixXd deficient(3, 2);
  deficient << 1, 2, 2, 4, 3, 6;
  EXPECT_THROW(expected_std_devs(deficient, 1.0), std::invalid_argument);
  EXPECT_THROW(expected_std_devs(W, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace modelgen
