// modelid design on the two-axis robot with limits (tests/bad_inputs/robots/): what it writes
// is checked by computations of the test's own, not the optimiser's: the written series
// evaluated on a 1 kHz grid against the description's limits times the margin, and the
// reported condition numbers recomputed from the numeric reference regressor stacked over one
// period (JacobiSVD of the unit-norm columns).

#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRobot = "tests/bad_inputs/robots/two_axes_limited.yaml";
constexpr double kPeriod = 2.0, kMargin = 0.9;

// The position-form series of a written design: q0, a, b per joint.
struct Series {
  double period = 0;
  std::vector<double> q0;
  std::vector<std::vector<double>> a, b;

  // q, dq, ddq of joint j at t (Swevers 2002 eq. 15 and its derivatives).
  void at(std::size_t j, double t, double& q, double& dq, double& ddq) const {
    const double wf = 2 * std::numbers::pi / period;
    q = q0[j], dq = 0, ddq = 0;
    for (std::size_t l = 0; l < a[j].size(); ++l) {
      const double w = static_cast<double>(l + 1) * wf, s = std::sin(w * t), c = std::cos(w * t);
      q += a[j][l] * s + b[j][l] * c;
      dq += w * (a[j][l] * c - b[j][l] * s);
      ddq -= w * w * (a[j][l] * s + b[j][l] * c);
    }
  }
};

Series read_series(const fs::path& path) {
  const YAML::Node root = YAML::LoadFile(path.string());
  Series series;
  series.period = root["period"].as<double>();
  EXPECT_EQ(root["form"].as<std::string>(), "position");
  for (const YAML::Node& joint : root["joints"]) {
    series.q0.push_back(joint["q0"].as<double>());
    series.a.push_back(joint["a"] ? joint["a"].as<std::vector<double>>() : std::vector<double>{});
    series.b.push_back(joint["b"] ? joint["b"].as<std::vector<double>>() : std::vector<double>{});
  }
  return series;
}

// The number after `key` on the report line that starts with `line_start`.
double reported(const std::string& out, const std::string& line_start, const std::string& key) {
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(line_start, 0) != 0) continue;
    const auto at = line.find(key);
    if (at == std::string::npos) break;
    return std::stod(line.substr(at + key.size()));
  }
  ADD_FAILURE() << "no '" << line_start << "' line with '" << key << "' in:\n" << out;
  return NAN;
}

CliRun design(const fs::path& output, const std::string& extra = "") {
  return modelid("design --robot " + quoted_source(kRobot) + " --period 2 --harmonics 2 --margin 0.9 "
                 "--samples 60 --starts 2 --seed 5 " + extra + " -o " + quoted(output));
}

TEST(ModelidDesign, StaysWithinTheLimitsOnAKilohertzGrid) {
  const fs::path dir = test_folder();
  const CliRun run = design(dir / "design.yaml");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Series series = read_series(dir / "design.yaml");
  ASSERT_EQ(series.q0.size(), 2u);
  EXPECT_EQ(series.period, kPeriod);
  // two_axes_limited.yaml: q [-1.5, 1.5], dq 7, ddq 20; q [-1, 1.5], dq 1.5, ddq 15.
  const double lower[2] = {-1.5, -1}, upper[2] = {1.5, 1.5}, dq_max[2] = {7, 1.5},
               ddq_max[2] = {20, 15};
  double most_used = 0;
  for (std::size_t j = 0; j < 2; ++j) {
    const double middle = (lower[j] + upper[j]) / 2, half = (upper[j] - lower[j]) / 2;
    for (int k = 0; k < 2000; ++k) {  // 1 kHz over the 2 s period
      double q, dq, ddq;
      series.at(j, k * 1e-3, q, dq, ddq);
      ASSERT_LE(std::abs(q - middle), kMargin * half * (1 + 1e-9)) << "joint " << j + 1 << " t " << k;
      ASSERT_LE(std::abs(dq), kMargin * dq_max[j] * (1 + 1e-9)) << "joint " << j + 1 << " t " << k;
      ASSERT_LE(std::abs(ddq), kMargin * ddq_max[j] * (1 + 1e-9)) << "joint " << j + 1 << " t " << k;
      most_used = std::max({most_used, std::abs(q - middle) / half, std::abs(dq) / dq_max[j],
                            std::abs(ddq) / ddq_max[j]});
    }
  }
  // A good excitation uses its room: some limit is nearly reached.
  EXPECT_GT(most_used, 0.8 * kMargin);
}

TEST(ModelidDesign, ReportedConditionNumberIsTheStackedRegressors) {
  const fs::path dir = test_folder();
  const CliRun run = design(dir / "design.yaml");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  ASSERT_NE(run.out.find("stacked over 60 samples"), std::string::npos) << run.out;
  ASSERT_NE(run.out.find("excite: 11 of 11"), std::string::npos) << run.out;
  const Series series = read_series(dir / "design.yaml");
  const RobotModel robot = load_robot(source_path(kRobot));
  const ReferenceModel model(robot.name, robot.tree, "", robot.drives);
  const int dof = model.dof(), p = model.num_base_params(), samples = 60;
  Eigen::MatrixXd W(samples * dof, p);
  for (int k = 0; k < samples; ++k) {
    Eigen::VectorXd q(dof), dq(dof), ddq(dof);
    for (int j = 0; j < dof; ++j) series.at(static_cast<std::size_t>(j), kPeriod * k / samples, q[j], dq[j], ddq[j]);
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows(dof, p);
    model.regressor(q.data(), dq.data(), ddq.data(), rows.data());
    W.middleRows(k * dof, dof) = rows;
  }
  const auto cond = [](const Eigen::MatrixXd& M) {
    const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(M).singularValues();
    return s[0] / s[s.size() - 1];
  };
  const Eigen::MatrixXd scaled = W * W.colwise().norm().cwiseInverse().asDiagonal();
  EXPECT_NEAR(reported(run.out, "design:", "unit columns "), cond(scaled), 1e-4 * cond(scaled));
  EXPECT_NEAR(reported(run.out, "design:", "unscaled "), cond(W), 1e-4 * cond(W));
  // The criterion (log cond) improved on the best random feasible start.
  EXPECT_LT(reported(run.out, "design:", "cond "), reported(run.out, "best random", "cond "));

  // The reported standard deviations (--noise 1: sigma^2 (W^T W)^-1) against a Monte-Carlo of
  // 200 OLS fits of the test's own W with unit Gaussian noise on every torque sample.
  std::mt19937 engine(11);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Eigen::VectorXd beta = Eigen::VectorXd::LinSpaced(p, 1.0, 2.0);
  const auto solver = W.colPivHouseholderQr();
  Eigen::MatrixXd fits(200, p);
  for (int r = 0; r < fits.rows(); ++r) {
    Eigen::VectorXd tau = W * beta;
    for (Eigen::Index i = 0; i < tau.size(); ++i) tau[i] += gauss(engine);
    fits.row(r) = solver.solve(tau).transpose();
  }
  const Eigen::RowVectorXd mean = fits.colwise().mean();
  const std::vector<std::string> names = model.base_param_names();
  for (int c = 0; c < p; ++c) {
    const double sd = std::sqrt((fits.col(c).array() - mean[c]).square().sum() / (fits.rows() - 1));
    // 200 runs: the sample sd is within 20% of the true one with overwhelming probability.
    EXPECT_NEAR(reported(run.out, "  " + names[static_cast<std::size_t>(c)] + " ", "sd "), sd, 0.2 * sd)
        << names[static_cast<std::size_t>(c)];
  }
}

TEST(ModelidDesign, SameSeedSameFile) {
  const fs::path dir = test_folder();
  ASSERT_EQ(design(dir / "one.yaml").exit_code, 0);
  ASSERT_EQ(design(dir / "two.yaml").exit_code, 0);
  EXPECT_EQ(read_text(dir / "one.yaml"), read_text(dir / "two.yaml"));
}

TEST(ModelidDesign, HeldAxisStaysWhereHeld) {
  const fs::path dir = test_folder();
  const CliRun run = design(dir / "held.yaml", "--axes 2 --hold q1=0.25");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Series series = read_series(dir / "held.yaml");
  EXPECT_EQ(series.q0[0], 0.25);
  EXPECT_TRUE(series.a[0].empty() && series.b[0].empty());
  // With axis 1 held, its friction and inertia columns carry nothing: fewer parameters.
  EXPECT_EQ(run.out.find("excite: 11 of 11"), std::string::npos) << run.out;
  const CliRun outside = design(dir / "bad.yaml", "--axes 2 --hold q1=2");
  EXPECT_EQ(outside.exit_code, 2);
  EXPECT_NE(outside.err.find("--hold: q1 = 2 is outside joint 1 ('J1')'s range [-1.5, 1.5]"),
            std::string::npos)
      << outside.err;
  EXPECT_FALSE(fs::exists(dir / "bad.yaml"));
}

// The largest |tau_j| / effort_j of a written design of two_axes_effort.yaml on a 1 kHz grid,
// from the closed form its comment derives: tau1 = 0.75 ddq1 + 0.05 ddq2,
// tau2 = 0.05 (ddq1 + ddq2), efforts 4 and 0.3 N m.
std::vector<double> effort_use(const Series& series) {
  std::vector<double> use(2, 0.0);
  for (int k = 0; k < 2000; ++k) {
    double q, dq, ddq1, ddq2;
    series.at(0, k * 1e-3, q, dq, ddq1);
    series.at(1, k * 1e-3, q, dq, ddq2);
    use[0] = std::max(use[0], std::abs(0.75 * ddq1 + 0.05 * ddq2) / 4);
    use[1] = std::max(use[1], std::abs(0.05 * (ddq1 + ddq2)) / 0.3);
  }
  return use;
}

TEST(ModelidDesign, EffortLimitsHoldTheAPrioriTorques) {
  const fs::path dir = test_folder();
  const std::string effort_robot = "tests/bad_inputs/robots/two_axes_effort.yaml";
  const std::string options = " --period 2 --harmonics 2 --margin 0.9 --samples 60 --starts 2 --seed 5 -o ";
  // The same robot without its effort limits: the design it gets asks for more torque than
  // the limits allow.
  std::string free_text = read_text(source_path(effort_robot));
  for (const char* effort : {", effort: 4", ", effort: 0.3"}) {
    const auto at = free_text.find(effort);
    ASSERT_NE(at, std::string::npos) << effort;
    free_text.erase(at, std::string(effort).size());
  }
  write_text(dir / "free_robot.yaml", free_text);
  const CliRun free_run = modelid("design --robot " + quoted(dir / "free_robot.yaml") + options +
                                  quoted(dir / "free.yaml"));
  ASSERT_EQ(free_run.exit_code, 0) << free_run.err;
  const std::vector<double> free_use = effort_use(read_series(dir / "free.yaml"));
  EXPECT_GT(std::max(free_use[0], free_use[1]), 1.0) << free_use[0] << " " << free_use[1];

  const CliRun run = modelid("design --robot " + quoted_source(effort_robot) + options +
                             quoted(dir / "held.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::vector<double> use = effort_use(read_series(dir / "held.yaml"));
  for (std::size_t j = 0; j < 2; ++j) {
    EXPECT_LE(use[j], kMargin * (1 + 1e-9)) << "joint " << j + 1;
  }
  // The torque is a limit the design runs into, not one it avoids by standing still.
  EXPECT_GT(std::max(use[0], use[1]), 0.95 * kMargin);
  EXPECT_NE(run.out.find("held within the effort limits times the margin"), std::string::npos)
      << run.out;
}

}  // namespace
}  // namespace modelgen::test
