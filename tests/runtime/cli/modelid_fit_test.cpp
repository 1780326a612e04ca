// modelid fit's additions as a user runs them, against independent computations: the essential
// parameters (--essential) are re-estimated here by least squares on the kept columns of a
// regressor built with the numeric reference, their %std ratio is below r_sigma and one more
// parameter would break it; EST.json holds the documented fields; the table marks poorly
// identified parameters; --plot writes the torques the estimate predicts; estimates of negative
// friction or rotor inertia get a warning, regrouped base parameters of any sign do not.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/estimation/identify.hpp"
#include "modelgen/estimation/least_squares.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/io/experiment/trajectory_csv.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/runtime/cli/modelid_cli_support.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using namespace modelgen::io;  // the data CSV (modelgen/io/experiment/trajectory_csv.hpp)

namespace fs = std::filesystem;
using test::CliRun;
using test::modelid;
using test::quoted;
using test::quoted_source;

// The bundled KR150 run: simulated with torque noise of 2 N m (README.md).
const std::string kData = "robots/data/kr150/excitation.csv";

ReferenceModel kr150_reference() {
  const modelgen::RobotModel description =
      modelgen::load_robot(test::source_path("robots/kr150.yaml"));
  return ReferenceModel(description.name, description.tree);
}

// The IDIM equations of `data` through the reference model: W (samples*dof x base), y.
void reference_equations(const ReferenceModel& model, const Trajectory& data, Eigen::MatrixXd& W,
                         Eigen::VectorXd& y) {
  const int n = model.dof(), nb = model.num_base_params();
  W.resize(data.t.size() * n, nb);
  y.resize(data.t.size() * n);
  std::vector<double> sample(static_cast<std::size_t>(n) * nb);
  for (Eigen::Index s = 0; s < data.t.size(); ++s) {
    const Eigen::VectorXd q = data.q.row(s), dq = data.dq.row(s), ddq = data.ddq.row(s);
    model.regressor(q.data(), dq.data(), ddq.data(), sample.data());
    for (int i = 0; i < n; ++i) {
      for (int b = 0; b < nb; ++b) W(s * n + i, b) = sample[i * nb + b];
      y[s * n + i] = data.tau(s, i);
    }
  }
}

Eigen::MatrixXd columns(const Eigen::MatrixXd& W, const std::vector<int>& indices) {
  Eigen::MatrixXd out(W.rows(), indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) out.col(k) = W.col(indices[k]);
  return out;
}

int index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto found = std::find(names.begin(), names.end(), name);
  EXPECT_NE(found, names.end()) << name;
  return static_cast<int>(found - names.begin());
}

// A truth file made for another description (its description_sha256 differs) would compare
// the estimate with numbers of other parameters: refused before the fit, saying the hashes
// differ.
TEST(ModelidFit, ATruthOfAnotherModelIsRefused) {
  const fs::path dir = test::test_folder();
  const fs::path forged = dir / "truth.json";
  test::write_text(forged, R"({"model": "tx40", "description_sha256": ")" + std::string(64, '0') +
                               R"(", "parameters": [{"name": "ZZ1R", "value": 1}]})");
  const CliRun run =
      modelid("fit --robot kr150 --data " + quoted_source("robots/data/kr150/excitation.csv") +
              " --method ols --truth " + quoted(forged));
  EXPECT_EQ(run.exit_code, 1) << run.out;
  EXPECT_NE(run.err.find(forged.string() + ": error: the truth belongs to another model: it was "
                                           "identified on 'tx40'"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("the hashes differ"), std::string::npos) << run.err;
}

TEST(ModelidFit, EssentialParametersKeepTheirRatioBelowRSigma) {
  const fs::path dir = test::test_folder();
  const ReferenceModel reference = kr150_reference();
  const std::vector<std::string>& names = reference.base_param_names();
  const Trajectory data = read_trajectory_csv(test::source_path(kData), reference.dof());
  Eigen::MatrixXd W;
  Eigen::VectorXd y;
  reference_equations(reference, data, W, y);

  std::set<std::string> kept_at_20;
  for (const double r_sigma : {20.0, 5.0}) {
    SCOPED_TRACE("r_sigma " + std::to_string(r_sigma));
    const fs::path estimate = dir / "est.json";
    const std::string ratio = r_sigma == 20.0 ? "" : " --r-sigma 5";  // 20 is the default
    const CliRun run = modelid("fit --robot kr150 --method ols --essential" + ratio + " --data " +
                               quoted_source(kData) + " -o " + quoted(estimate));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const nlohmann::json essential = nlohmann::json::parse(test::read_text(estimate))["essential"];
    ASSERT_TRUE(essential.is_object());
    EXPECT_EQ(essential["r_sigma"].get<double>(), r_sigma);
    const auto kept = essential["kept"].get<std::vector<std::string>>();
    const auto eliminated = essential["eliminated"].get<std::vector<std::string>>();
    ASSERT_FALSE(kept.empty());
    ASSERT_FALSE(eliminated.empty()) << "these data identify every parameter well";
    // Every base parameter is either kept or eliminated, none both.
    std::set<std::string> all(kept.begin(), kept.end());
    all.insert(eliminated.begin(), eliminated.end());
    EXPECT_EQ(all.size(), names.size());
    EXPECT_EQ(all, std::set<std::string>(names.begin(), names.end()));
    if (r_sigma == 20.0) kept_at_20.insert(kept.begin(), kept.end());
    for (const std::string& name : kept) {
      if (r_sigma != 20.0) {
        EXPECT_TRUE(kept_at_20.count(name)) << "a smaller ratio keeps " << name;
      }
    }

    // The kept parameters, re-estimated here by OLS on the reference's columns.
    std::vector<int> kept_columns;
    for (const std::string& name : kept) kept_columns.push_back(index_of(names, name));
    std::vector<std::string> kept_names = kept;
    const LeastSquaresResult fit = fit_ols(columns(W, kept_columns), y, kept_names);
    ASSERT_EQ(essential["parameters"].size(), kept.size());
    double largest = 0, smallest = INFINITY;
    for (std::size_t k = 0; k < kept.size(); ++k) {
      const nlohmann::json& p = essential["parameters"][k];
      EXPECT_EQ(p["name"], kept[k]);
      EXPECT_NEAR(p["value"].get<double>(), fit.value[k],
                  1e-7 * std::max(1.0, std::abs(fit.value[k])))
          << kept[k];
      EXPECT_NEAR(p["rel_std"].get<double>(), fit.rel_std_dev[k], 1e-6 * fit.rel_std_dev[k]);
      largest = std::max(largest, fit.rel_std_dev[k]);
      smallest = std::min(smallest, fit.rel_std_dev[k]);
    }
    EXPECT_LT(largest / smallest, r_sigma);
    // With the last eliminated parameter back, the ratio was not below r_sigma and that
    // parameter had the largest %std.
    std::vector<int> before = kept_columns;
    before.push_back(index_of(names, eliminated.back()));
    std::vector<std::string> before_names = kept_names;
    before_names.push_back(eliminated.back());
    const LeastSquaresResult previous = fit_ols(columns(W, before), y, before_names);
    Eigen::Index worst = 0;
    EXPECT_GE(previous.rel_std_dev.maxCoeff(&worst) / previous.rel_std_dev.minCoeff(), r_sigma);
    EXPECT_EQ(worst, static_cast<Eigen::Index>(kept.size()));
    // The screen names every eliminated parameter.
    EXPECT_NE(run.out.find("eliminated, first to last (" + std::to_string(eliminated.size()) + ")"),
              std::string::npos)
        << run.out;
    for (const std::string& name : eliminated) {
      EXPECT_NE(run.out.find(" " + name), std::string::npos) << name;
    }
  }
}

TEST(ModelidFit, EstimateFileTableAndPlots) {
  const fs::path dir = test::test_folder();
  const fs::path estimate = dir / "est.json", plots = dir / "plots";
  const CliRun run = modelid("fit --robot kr150 --method wls --data " + quoted_source(kData) +
                             " -o " + quoted(estimate) + " --plot " + quoted(plots));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json json = nlohmann::json::parse(test::read_text(estimate));
  for (const char* key : {"model", "description_sha256", "method", "parameters", "rel_error_norm",
                          "rms_per_axis", "condition_number", "residual_std", "samples", "data"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["model"], "kr150");
  EXPECT_EQ(json["method"], "IDIM-WLS");
  EXPECT_EQ(json["data"], nlohmann::json::array({test::source_path(kData)}));
  EXPECT_FALSE(json.contains("essential"));
  const ReferenceModel reference = kr150_reference();
  const int n = reference.dof();
  const Trajectory data = read_trajectory_csv(test::source_path(kData), n);
  EXPECT_EQ(json["samples"].get<long long>(), data.t.size());
  ASSERT_EQ(json["parameters"].size(), static_cast<std::size_t>(reference.num_base_params()));

  // The table marks exactly the parameters above 10 %std.
  Eigen::VectorXd beta(reference.num_base_params());
  for (std::size_t b = 0; b < json["parameters"].size(); ++b) {
    const nlohmann::json& p = json["parameters"][b];
    EXPECT_EQ(p["name"], reference.base_param_names()[b]);
    beta[b] = p["value"].get<double>();
    const bool poor = p["rel_std"].is_null() || p["rel_std"].get<double>() > 10;
    std::string name = p["name"];
    name.resize(std::max<std::size_t>(name.size(), 9), ' ');
    const std::size_t line = run.out.find("\n  " + name + " ");
    ASSERT_NE(line, std::string::npos) << name;
    const std::string row = run.out.substr(line + 1, run.out.find('\n', line + 1) - line - 1);
    EXPECT_EQ(row.back() == '*', poor) << row;
  }

  // torques.csv: the measured torques and those of the estimate, computed here by the
  // reference model; its error columns give the rms per axis of EST.json.
  const test::CsvTable table = test::read_csv(plots / "torques.csv");
  EXPECT_EQ(table.header, test::expected_header({"tau", "tau_pred", "error"}, n));
  ASSERT_EQ(table.rows.size(), static_cast<std::size_t>(data.t.size()));
  std::vector<double> tau(n), error_squares(n, 0.0);
  for (std::size_t s = 0; s < table.rows.size(); ++s) {
    const Eigen::VectorXd q = data.q.row(s), dq = data.dq.row(s), ddq = data.ddq.row(s);
    reference.inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau.data());
    for (int j = 0; j < n; ++j) {
      const std::string k = std::to_string(j + 1);
      EXPECT_EQ(table.at(s, "tau" + k), data.tau(s, j));
      EXPECT_NEAR(table.at(s, "tau_pred" + k), tau[j], 1e-9 * std::max(1.0, std::abs(tau[j])));
      error_squares[j] += std::pow(data.tau(s, j) - tau[j], 2);
    }
  }
  for (int j = 0; j < n; ++j) {
    const double rms = std::sqrt(error_squares[j] / data.t.size());
    EXPECT_NEAR(json["rms_per_axis"][j].get<double>(), rms, 1e-8 * rms) << j;
  }
  EXPECT_TRUE(fs::exists(plots / "plot.gp"));
}

// The bundled run's truth is physical: at most warnings that say "not significantly" (noisy
// estimates of small true values), none for regrouped parameters such as XX2R, negative here. The
// same truth with a negative viscous friction and rotor inertia on axis 3 (both unregrouped base
// parameters of the KR150), simulated without noise: both are flagged, significantly (their std is
// ~0), and nothing else is.
TEST(ModelidFit, ImpossibleEstimatesAreFlagged) {
  const fs::path dir = test::test_folder("fit");
  const CliRun bundled = modelid("fit --robot kr150 --data " + quoted_source(kData) +
                                 " --method wls -o " + quoted(dir / "bundled.json"));
  ASSERT_EQ(bundled.exit_code, 0) << bundled.err;
  const nlohmann::json estimate = nlohmann::json::parse(test::read_text(dir / "bundled.json"));
  std::set<std::string> flagged;
  std::istringstream bundled_lines(bundled.err);
  for (std::string line; std::getline(bundled_lines, line);) {
    const std::string start = "modelid fit: warning: ";
    if (line.find("cannot be") == std::string::npos) continue;
    ASSERT_EQ(line.rfind(start, 0), 0u) << line;
    flagged.insert(line.substr(start.size(), line.find(' ', start.size()) - start.size()));
    // Noise can push a small true value below 0, but not beyond 3 std.
    EXPECT_NE(line.find("not significantly"), std::string::npos) << line;
  }
  bool negative_regrouped = false;
  for (const nlohmann::json& p : estimate["parameters"]) {
    const std::string name = p["name"];
    if (name.back() != 'R' || p["value"] >= 0) continue;
    negative_regrouped = true;
    EXPECT_EQ(flagged.count(name), 0u) << name << " is regrouped: any sign is possible";
  }
  EXPECT_TRUE(negative_regrouped) << "no negative regrouped parameter left to test the exemption";

  // simulate refuses a truth no robot has (Fv3 = -20, Ia3 = -1.5: impossible_truth_test.cpp):
  // data of such a robot are made by taking 40 dq3 + 7.5 ddq3 off the torque of axis 3 of the
  // true robot (Fv3 20, Ia3 6).
  const CliRun simulated = modelid(
      "simulate --robot kr150 --params " + quoted_source("robots/data/kr150/true.json") +
      " --trajectory " + quoted_source("robots/data/kr150/excitation.yaml") +
      " --noise 0 --sample-time 0.01 -o " + quoted(dir / "true.csv"));
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  Trajectory data = read_trajectory_csv((dir / "true.csv").string(), 6);
  ASSERT_TRUE(data.has_velocity);
  data.tau.col(2) -= 40 * data.dq.col(2) + 7.5 * data.ddq.col(2);
  write_trajectory_csv((dir / "data.csv").string(), data);
  const CliRun fit =
      modelid("fit --robot kr150 --data " + quoted(dir / "data.csv") + " --method ols");
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  std::istringstream lines(fit.err);
  std::vector<std::string> warnings;
  for (std::string line; std::getline(lines, line);) {
    if (line.find("cannot be") != std::string::npos) warnings.push_back(line);
  }
  ASSERT_EQ(warnings.size(), 2u) << fit.err;
  EXPECT_EQ(warnings[0].rfind("modelid fit: warning: Ia3 = -1.5 is negative: a rotor inertia "
                              "cannot be",
                              0),
            0u)
      << warnings[0];
  EXPECT_EQ(warnings[1].rfind("modelid fit: warning: Fv3 = -20 is negative: a friction "
                              "coefficient cannot be",
                              0),
            0u)
      << warnings[1];
}

}  // namespace
}  // namespace modelgen

namespace modelgen {
namespace {

TEST(ModelidFit, MinSpeedLeavesOutTheSamplesWhereAJointIsSlow) {
  // The bundled run gives dq: no decimation, so the samples left out are those where some
  // |dq_j| < 0.1, counted here from the file.
  const Trajectory x =
      read_trajectory_csv(test::source_path(kData), 6, EffortColumns::kRequired);
  Eigen::Index slow = 0;
  for (Eigen::Index s = 0; s < x.t.size(); ++s) {
    if ((x.dq.row(s).array().abs() < 0.1).any()) ++slow;
  }
  ASSERT_GT(slow, 0);
  const CliRun run = test::modelid("fit --robot kr150 --data " + quoted_source(kData) +
                                   " --method wls --min-speed 0.1");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string line = "--min-speed: " + std::to_string(slow) + " of " +
                           std::to_string(x.t.size()) + " samples left out";
  EXPECT_NE(run.out.find(line), std::string::npos) << line << "\n" << run.out;
  EXPECT_NE(run.out.find(std::to_string(x.t.size() - slow) + " samples"), std::string::npos)
      << run.out;

  const CliRun everything =
      test::modelid("fit --robot kr150 --data " + quoted_source(kData) + " --method wls --min-speed 50");
  EXPECT_EQ(everything.exit_code, 1);
  EXPECT_NE(everything.err.find("leaves out every sample"), std::string::npos) << everything.err;
  const CliRun wrong =
      test::modelid("fit --robot kr150 --data " + quoted_source(kData) + " --method wls --min-speed 0.1,0.2");
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_NE(wrong.err.find("--min-speed needs one speed or 6 (one per joint)"), std::string::npos)
      << wrong.err;
}

}  // namespace
}  // namespace modelgen

namespace modelgen {
namespace {

// With --min-speed the fit weighs the equations near reversals down, so its relative error
// norm covers only what it weighs; beside it stands the norm over every sample, recomputed here
// from the estimate with the numeric reference's regressor (this run is not decimated).
TEST(ModelidFit, MinSpeedPrintsTheErrorOverEverySampleBesideTheWeighedOne) {
  const fs::path dir = test::test_folder();
  const ReferenceModel reference = kr150_reference();
  const Trajectory data = read_trajectory_csv(test::source_path(kData), reference.dof());
  Eigen::MatrixXd W;
  Eigen::VectorXd y;
  reference_equations(reference, data, W, y);
  const fs::path estimate = dir / "est.json";
  const CliRun run = modelid("fit --robot kr150 --data " + quoted_source(kData) +
                             " --method wls --min-speed 0.1 -o " + quoted(estimate));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string marker = " over the equations the fit weighs (";
  const std::size_t at = run.out.find(marker);
  ASSERT_NE(at, std::string::npos) << run.out;
  const double printed = std::stod(run.out.substr(at + marker.size()));
  EXPECT_NE(run.out.find(" over every sample, reversals included)"), std::string::npos);

  const nlohmann::json file = nlohmann::json::parse(test::read_text(estimate));
  const std::vector<std::string>& names = reference.base_param_names();
  Eigen::VectorXd beta(static_cast<Eigen::Index>(names.size()));
  for (const nlohmann::json& p : file["parameters"]) {
    beta[index_of(names, p["name"].get<std::string>())] = p["value"].get<double>();
  }
  const double every_sample = (y - W * beta).norm() / y.norm();
  EXPECT_NEAR(printed, every_sample, 1e-4 * every_sample + 1e-4) << run.out;
  // The weighed figure leaves the slow samples out, so it differs from the one over all.
  const std::size_t norm_at = run.out.find("relative error norm of the torques ");
  ASSERT_NE(norm_at, std::string::npos);
  const double weighed = std::stod(run.out.substr(norm_at + 35));
  EXPECT_GT(std::abs(weighed - every_sample), 1e-3 * every_sample) << run.out;

  // Without weighting there is one figure.
  const CliRun plain =
      modelid("fit --robot kr150 --data " + quoted_source(kData) + " --method wls --min-speed 0");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(plain.out.find(marker), std::string::npos) << plain.out;
}

TEST(ModelidFit, ADecimationFactorThatCannotBeStagedIsRefused) {
  const CliRun run = test::modelid("fit --robot kr150 --data " + quoted_source(kData) +
                                   " --method wls --decimate 22");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--decimate: decimation factor 22 has the prime factor 11, above 10"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("use 21 or 24"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace modelgen
