// modelid fit --method ml (Swevers et al. 2002, eq. 18, approaches 1 and 3 of section 4) run as a
// user would: a KR150-like periodic experiment (the Table 1 excitation of axes 3-6, four periods)
// simulated here with the runtime's ReferenceDriveModel from a known load (Table 2), efficiencies
// R_z below 1, friction and seeded noise, written as joint-side torques tau = K^T tau_M; the
// description is robots/kr150.yaml plus `known:` link values. Checks the load in EST.json
// against the simulated truth within its reported standard deviations (approach 3), the bias of
// approach 1 (R_z taken as 1), and the usage errors.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Eigenvalues>

#include "modelgen/ml/drive_model.hpp"
#include "modelgen/ml/load_parameters.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/runtime/cli/modelid_cli_support.hpp"
#include "tests/support/kdl_oracle.hpp"
#include "tests/support/kr150_load_scenario.hpp"

namespace modelgen::test {
namespace {

using Scenario = Kr150LoadScenario;  // its trajectory, load, drive parameters and noise levels
constexpr double kPeriod = Scenario::kPeriod;
constexpr int kSamplesPerPeriod = Scenario::kSamples;
constexpr int kPeriods = 4;
// Noise standard deviation on the averaged motor torques (N m); per sample sqrt(P) times this.
constexpr const double* kSigma = Scenario::kSigma;
constexpr const double* kJM = Scenario::kJM;
constexpr const double* kRv = Scenario::kRv;
constexpr const double* kRc = Scenario::kRc;
constexpr const double* kRz = Scenario::kRz;

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// The scenario's files in `dir`: robot.yaml (kr150.yaml plus `known:` XXj..Mj of links 1-7, link
// 7 zero as it carries only the load, and Iaj = JMj: the wrist coupling has a unit diagonal),
// data.csv (t, q1..q6, tau1..tau6, joint side).
void write_scenario(const std::filesystem::path& dir) {
  const std::string description_text = read_text(source_path("robots/kr150.yaml"));
  const modelgen::RobotModel description = modelgen::load_robot(source_path("robots/kr150.yaml"));
  Random random(2002);
  const Eigen::VectorXd p = random_physical_parameters(description.tree, random);
  std::map<std::string, double> known;
  for (std::size_t k = 0; k < description.tree.params.size(); ++k) {
    const std::string& name = description.tree.params[k].name;
    const char last = name.back();
    if (name.find_first_of("0123456789") == std::string::npos) continue;
    const std::string stem = name.substr(0, name.find_first_of("0123456789"));
    if (stem == "XX" || stem == "XY" || stem == "XZ" || stem == "YY" || stem == "YZ" ||
        stem == "ZZ" || stem == "MX" || stem == "MY" || stem == "MZ" || stem == "M") {
      known[name] = last == '7' ? 0.0 : p[static_cast<Eigen::Index>(k)];
    }
  }
  for (int j = 0; j < 6; ++j) known["Ia" + std::to_string(j + 1)] = kJM[j];
  std::string yaml = description_text + "known:\n";
  for (const auto& [name, value] : known) yaml += "  " + name + ": " + number(value) + "\n";
  write_text(dir / "robot.yaml", yaml);
  // The same a-priori values as a --known file for the shipped robots/kr150.yaml (JMj = Iaj).
  std::string json = "{";
  for (const auto& [name, value] : known) {
    json += (json.size() > 1 ? ", \"" : "\"") +
            (name.compare(0, 2, "Ia") == 0 ? "JM" + name.substr(2) : name) + "\": " + number(value);
  }
  write_text(dir / "known.json", json + "}");

  // Motor torques of the true model: links' own values plus the load on link 7.
  DriveChain drive = DriveChain::identity(6);
  drive.motor_from_joint = description.drives.motor_from_joint;
  ReferenceDriveModel model(description.tree, drive);
  const std::vector<std::string>& names = model.param_names();
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(model.num_params());
  const auto index = [&names](const std::string& name) {
    const auto found = std::find(names.begin(), names.end(), name);
    EXPECT_NE(found, names.end()) << name;
    return found - names.begin();
  };
  for (const auto& [name, value] : known) {
    if (name.compare(0, 2, "Ia") != 0) theta[index(name)] = value;
  }
  for (int j = 0; j < 6; ++j) {
    const std::string n = std::to_string(j + 1);
    theta[index("JM" + n)] = kJM[j];
    theta[index("Rv" + n)] = kRv[j];
    theta[index("Rc" + n)] = kRc[j];
    theta[index("Rz" + n)] = kRz[j];
  }
  const std::array<double, 10> load = standard_from_load(table2_load());
  const char* stems[10] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};
  for (int m = 0; m < 10; ++m) theta[index(std::string(stems[m]) + "7")] += load[m];

  const int samples = kSamplesPerPeriod * kPeriods;
  Eigen::MatrixXd q(samples, 6), dq(samples, 6), ddq(samples, 6);
  for (int s = 0; s < samples; ++s) {
    Eigen::VectorXd qs, dqs, ddqs;
    table1_state(kPeriod * s / kSamplesPerPeriod, true, qs, dqs, ddqs);
    q.row(s) = qs.transpose();
    dq.row(s) = dqs.transpose();
    ddq.row(s) = ddqs.transpose();
  }
  model.set_samples(q, dq, ddq);
  std::ostringstream csv;
  csv << "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6\n";
  for (int s = 0; s < samples; ++s) {
    Eigen::VectorXd tau_M(6);
    model.torque(s, theta.data(), tau_M.data());
    for (int i = 0; i < 6; ++i) tau_M[i] += std::sqrt(kPeriods) * kSigma[i] * random.normal();
    const Eigen::VectorXd tau = drive.motor_from_joint.transpose() * tau_M;
    csv << number(kPeriod * s / kSamplesPerPeriod);
    for (int j = 0; j < 6; ++j) csv << "," << number(q(s, j));
    for (int j = 0; j < 6; ++j) csv << "," << number(tau[j]);
    csv << "\n";
  }
  write_text(dir / "data.csv", csv.str());
}

// The fits of the test's description through the numeric reference (--no-compile): the
// independent computation the generated drive models are compared with.
std::string fit_arguments(const std::filesystem::path& dir, const std::string& approach,
                          const std::string& output = "") {
  return "fit --method ml --approach " + approach + " --robot " + quoted(dir / "robot.yaml") +
         " --data " + quoted(dir / "data.csv") + " --periodic --period 36.96 --no-compile -o " +
         quoted(dir / (output.empty() ? "est" + approach + ".json" : output));
}

// The load in EST.json as 10 values in LoadParameters::to_vector() order ("load" or its "std").
std::array<double, 10> load_values(const nlohmann::json& load) {
  const auto value = [](const nlohmann::json& v) {
    return v.is_null() ? std::nan("") : v.get<double>();
  };
  return {value(load["m"]),       value(load["c"][0]),    value(load["c"][1]),
          value(load["c"][2]),    value(load["I"]["xx"]), value(load["I"]["yy"]),
          value(load["I"]["zz"]), value(load["I"]["xy"]), value(load["I"]["xz"]),
          value(load["I"]["yz"])};
}

TEST(ModelidMl, Approach3RecoversTheLoadAndApproach1IsBiased) {
  const std::filesystem::path dir = test_folder();
  write_scenario(dir);
  const std::array<double, 10> truth = table2_load().to_vector();
  const std::vector<std::string>& names = load_param_names();

  const CliRun run3 = modelid(fit_arguments(dir, "3"));
  ASSERT_EQ(run3.exit_code, 0) << run3.out << run3.err;
  std::printf("%s%s", run3.out.c_str(), run3.err.c_str());
  EXPECT_EQ(run3.err.find("warning"), std::string::npos) << run3.err;
  const nlohmann::json est3 = nlohmann::json::parse(read_text(dir / "est3.json"));
  EXPECT_EQ(est3["method"], "ML approach 3");
  EXPECT_EQ(est3["identifiability"]["rank"], 22);
  EXPECT_EQ(est3["identifiability"]["unknowns"], 22);
  EXPECT_TRUE(est3["load"]["warnings"].empty());
  const std::array<double, 10> load3 = load_values(est3["load"]);
  const std::array<double, 10> sd3 = load_values(est3["load"]["std"]);
  for (int k = 0; k < 10; ++k) {
    EXPECT_LT(std::abs(load3[k] - truth[k]), 4 * sd3[k])
        << names[k] << " estimate " << load3[k] << " sd " << sd3[k] << " truth " << truth[k];
  }
  // The drive unknowns: Rv, Rc, Rz of axes 3-6, within their standard deviations.
  ASSERT_EQ(est3["parameters"].size(), 12u);
  for (const nlohmann::json& p : est3["parameters"]) {
    const std::string name = p["name"];
    const int j = name.back() - '1';
    const double exact = name[1] == 'v' ? kRv[j] : (name[1] == 'c' ? kRc[j] : kRz[j]);
    EXPECT_LT(std::abs(p["value"].get<double>() - exact), 4 * p["std"].get<double>()) << name;
  }
  // The residuals are the noise: rms error per fitted motor near its sigma (the CSV's noise is
  // sqrt(P) sigma per sample, the average's sigma).
  for (int i = 2; i < 6; ++i) {
    EXPECT_NEAR(est3["rms_per_axis"][i].get<double>(), kSigma[i], 0.15 * kSigma[i]) << i;
  }

  // The shipped description with the same values from --known: modelid uses the compiled-in
  // generated drive model (flattened analytic Jacobians) instead of the numeric reference's, an
  // independent computation that must give the same estimate.
  const CliRun generated =
      modelid("fit --method ml --approach 3 --robot " + quoted_source("robots/kr150.yaml") +
              " --known " + quoted(dir / "known.json") + " --data " + quoted(dir / "data.csv") +
              " --periodic --period 36.96 -o " + quoted(dir / "generated.json"));
  ASSERT_EQ(generated.exit_code, 0) << generated.out << generated.err;
  EXPECT_NE(generated.out.find("drive model: generated kr150 (analytic Jacobians)"),
            std::string::npos)
      << generated.out;
  EXPECT_NE(run3.out.find("drive model: numeric reference"), std::string::npos) << run3.out;
  // The test's description compiled on first use (docs/compiled-models.md): its generated
  // drive model too.
  std::string compiled_arguments = fit_arguments(dir, "3", "compiled.json");
  compiled_arguments.replace(compiled_arguments.find(" --no-compile"), 13, "");
  const CliRun compiled = modelid(compiled_arguments);
  ASSERT_EQ(compiled.exit_code, 0) << compiled.out << compiled.err;
  EXPECT_NE(compiled.out.find("compiled from its description (analytic Jacobians)"),
            std::string::npos)
      << compiled.out;
  const nlohmann::json est_generated = nlohmann::json::parse(read_text(dir / "generated.json"));
  const std::array<double, 10> load_generated = load_values(est_generated["load"]);
  const std::array<double, 10> load_compiled =
      load_values(nlohmann::json::parse(read_text(dir / "compiled.json"))["load"]);
  for (int k = 0; k < 10; ++k) {
    EXPECT_NEAR(load_compiled[k], load3[k], 1e-6 * sd3[k]) << names[k];
    EXPECT_NEAR(load_generated[k], load3[k], 1e-6 * sd3[k]) << names[k];
  }

  // All three approaches compared (Tables 2-3), with the exact values: approach 1 takes the
  // efficiencies as 1 while they are 0.85-0.9, and its load is off by far more than approach 3's.
  std::string truth_json = "{";
  for (int k = 0; k < 10; ++k) truth_json += "\"" + names[k] + "\": " + number(truth[k]) + ", ";
  for (int j = 2; j < 6; ++j) {
    const std::string n = std::to_string(j + 1);
    truth_json += "\"Rv" + n + "\": " + number(kRv[j]) + ", \"Rc" + n + "\": " + number(kRc[j]) +
                  ", \"Rz" + n + "\": " + number(kRz[j]) + (j < 5 ? ", " : "}");
  }
  write_text(dir / "truth.json", truth_json);
  const CliRun all = modelid(fit_arguments(dir, "all") + " --truth " + quoted(dir / "truth.json"));
  ASSERT_EQ(all.exit_code, 0) << all.out << all.err;
  std::printf("%s%s", all.out.c_str(), all.err.c_str());
  EXPECT_NE(all.out.find("errors (estimate - exact)"), std::string::npos);
  EXPECT_NE(all.out.find("rms torque errors (N m)"), std::string::npos);
  const nlohmann::json est = nlohmann::json::parse(read_text(dir / "estall.json"));
  EXPECT_EQ(est["method"], "ML approaches 1-3");
  ASSERT_EQ(est["approaches"].size(), 3u);
  const nlohmann::json& est1 = est["approaches"][0];
  EXPECT_EQ(est1["method"], "ML approach 1");
  EXPECT_EQ(est1["identifiability"]["unknowns"], 22);  // + JM3-JM6, unknown in approach 1
  EXPECT_EQ(est1["iterations"], 0);
  EXPECT_EQ(est["approaches"][1]["identifiability"]["unknowns"], 18);  // R_z fixed to 1
  // Approach 3 within the comparison is the approach-3 fit above.
  EXPECT_NEAR(load_values(est["approaches"][2]["load"])[0], load3[0], 1e-9);
  const std::array<double, 10> load1 = load_values(est1["load"]);
  EXPECT_GT(std::abs(load1[0] - truth[0]), 10 * std::abs(load3[0] - truth[0]))
      << "approach 1 mass " << load1[0];
  EXPECT_GT(std::abs(load1[0] - truth[0]), 10 * sd3[0]) << "approach 1 mass " << load1[0];
}

// The bundled demo (README's first command): every estimate that cannot be a physical value
// by the rule written out here, independently of the library's, gets a warning line on stderr
// naming its approach, "not significantly" when value + 3 std reaches 0. The case: the
// demo's Rv3 comes out negative, and nothing said so.
TEST(ModelidMl, BundledDemoWarnsAboutImpossibleEstimates) {
  const std::filesystem::path dir = test_folder("ml");
  const CliRun simulated =
      modelid("simulate --robot " + quoted_source("robots/kr150.yaml") + " --drive " +
              quoted_source("robots/data/kr150/load/drive_truth.json") + " --trajectory " +
              quoted_source("robots/data/kr150/load/table1.yaml") +
              " --noise 345,345,345,133,126,123 --seed 2002 --sample-time 0.024 --periods 10 "
              "--ignore-limits -o " +
              quoted(dir / "load.csv"));
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  const CliRun fit = modelid(
      "fit --method ml --approach all --robot " + quoted_source("robots/kr150.yaml") + " --known " +
      quoted_source("robots/data/kr150/load/known.json") + " --data " + quoted(dir / "load.csv") +
      " --periodic --period 36.96 -o " + quoted(dir / "est.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const nlohmann::json est = nlohmann::json::parse(read_text(dir / "est.json"));
  // Friction coefficients (Rv, Rc) and rotor inertias (JM) of one joint must be >= 0, the load
  // mass > 0.
  const auto bounded = [](const std::string& name) {
    for (const std::string stem : {"Rv", "Rc", "JM"}) {
      if (name.size() > stem.size() && name.compare(0, stem.size(), stem) == 0 &&
          name.find_first_not_of("0123456789", stem.size()) == std::string::npos) {
        return true;
      }
    }
    return false;
  };
  std::istringstream err_lines(fit.err);
  std::vector<std::string> warnings;
  for (std::string line; std::getline(err_lines, line);) {
    if (line.find("cannot be") != std::string::npos) warnings.push_back(line);
  }
  std::size_t expected = 0;
  bool rv3_flagged = false;
  for (const nlohmann::json& approach : est["approaches"]) {
    const std::string method = approach["method"];  // "ML approach N"
    const std::string prefix =
        "modelid fit: warning: approach " + method.substr(method.size() - 1) + ": ";
    std::vector<std::tuple<std::string, double, double>> checked;
    for (const nlohmann::json& p : approach["parameters"]) {
      if (p["value"].is_null() || !bounded(p["name"])) continue;
      checked.emplace_back(p["name"], p["value"], p["std"].is_null() ? NAN : double(p["std"]));
    }
    const nlohmann::json& load = approach["load"];
    if (!load["m"].is_null()) {
      checked.emplace_back("load_m", load["m"],
                           load["std"]["m"].is_null() ? NAN : double(load["std"]["m"]));
    }
    for (const auto& [name, value, sd] : checked) {
      const bool mass = name == "load_m";
      const bool impossible = mass ? value <= 0 : value < 0;
      const std::string start = prefix + name + " = ";
      const auto line = std::find_if(warnings.begin(), warnings.end(),
                                     [&](const std::string& w) { return w.rfind(start, 0) == 0; });
      if (!impossible) {
        EXPECT_TRUE(line == warnings.end()) << *line;
        continue;
      }
      ++expected;
      if (name == "Rv3") rv3_flagged = true;
      ASSERT_NE(line, warnings.end()) << start << " " << value << " not flagged:\n" << fit.err;
      const bool significant = std::isfinite(sd) && value + 3 * sd < 0;
      EXPECT_EQ(line->find("not significantly") == std::string::npos, significant) << *line;
      const std::string quantity = mass             ? "a mass"
                                   : name[0] == 'J' ? "a rotor inertia"
                                                    : "a friction coefficient";
      EXPECT_NE(line->find(quantity + " cannot be"), std::string::npos) << *line;
    }
  }
  EXPECT_EQ(warnings.size(), expected) << fit.err;
  EXPECT_TRUE(rv3_flagged) << "the demo's Rv3 is no longer negative in any approach:\n" << fit.out;
}

// fit --method ml --physical on the bundled demo: each approach's estimate becomes one no
// physical law forbids, checked here from the numbers in EST.json (friction and rotor inertias
// >= 0, efficiencies in (0, 1], a load whose inertia about its centre of gravity is positive
// definite with the triangle inequalities), at little cost in fit.
TEST(ModelidMl, PhysicalMakesEveryApproachConsistent) {
  const std::filesystem::path dir = test_folder("ml");
  const CliRun simulated =
      modelid("simulate --robot " + quoted_source("robots/kr150.yaml") + " --drive " +
              quoted_source("robots/data/kr150/load/drive_truth.json") + " --trajectory " +
              quoted_source("robots/data/kr150/load/table1.yaml") +
              " --noise 345,345,345,133,126,123 --seed 2002 --sample-time 0.024 --periods 10 "
              "--ignore-limits -o " +
              quoted(dir / "load.csv"));
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  const CliRun fit = modelid(
      "fit --method ml --approach all --robot " + quoted_source("robots/kr150.yaml") + " --known " +
      quoted_source("robots/data/kr150/load/known.json") + " --data " + quoted(dir / "load.csv") +
      " --periodic --period 36.96 --physical -o " + quoted(dir / "est.json"));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_EQ(fit.err.find("cannot be"), std::string::npos) << fit.err;
  const nlohmann::json est = nlohmann::json::parse(read_text(dir / "est.json"));
  ASSERT_EQ(est["approaches"].size(), 3u);
  for (const nlohmann::json& approach : est["approaches"]) {
    const std::string method = approach["method"];
    EXPECT_NE(method.find("(physically consistent)"), std::string::npos) << method;
    ASSERT_TRUE(approach.contains("physical")) << method;
    const nlohmann::json& physical = approach["physical"];
    // The unconstrained estimate had a negative viscous friction on axis 3 (the bundled demo's
    // known flaw), and that bound binds.
    bool rv3 = false;
    for (const nlohmann::json& v : physical["unconstrained_violations"]) {
      rv3 = rv3 || std::string(v).rfind("Rv3 = -", 0) == 0;
    }
    EXPECT_TRUE(rv3) << method;
    bool rv3_binds = false;
    for (const nlohmann::json& b : physical["binding_constraints"]) rv3_binds |= b == "Rv3 >= 0";
    EXPECT_TRUE(rv3_binds) << method;
    for (const nlohmann::json& p : approach["parameters"]) {
      if (p["value"].is_null()) continue;
      const std::string name = p["name"];
      const double value = p["value"];
      if (name.rfind("Rz", 0) == 0) {
        EXPECT_GT(value, 0) << method << " " << name;
        EXPECT_LE(value, 1) << method << " " << name;
      } else {
        EXPECT_GE(value, 0) << method << " " << name;
      }
    }
    const nlohmann::json& load = approach["load"];
    ASSERT_FALSE(load["m"].is_null()) << method;
    EXPECT_GT(double(load["m"]), 0) << method;
    const nlohmann::json& I = load["I"];
    Eigen::Matrix3d inertia;
    inertia << double(I["xx"]), double(I["xy"]), double(I["xz"]), double(I["xy"]),
        double(I["yy"]), double(I["yz"]), double(I["xz"]), double(I["yz"]), double(I["zz"]);
    const Eigen::Vector3d moments =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia).eigenvalues();
    EXPECT_GT(moments[0], 0) << method;
    EXPECT_LE(moments[2], moments[0] + moments[1]) << method;
    // Consistency costs little: rms torque errors within 5 % of the unconstrained ones.
    const std::vector<double> rms = approach["rms_per_axis"];
    const std::vector<double> before = physical["unconstrained"]["rms_per_axis"];
    for (std::size_t i = 0; i < rms.size(); ++i) {
      EXPECT_LE(rms[i], 1.05 * before[i] + 1e-12) << method << " motor " << i + 1;
    }
  }
}

TEST(ModelidMl, UsageErrors) {
  const std::filesystem::path dir = test_folder();
  write_text(dir / "data.csv", "t,q1,q2,q3,q4,q5,q6,tau1,tau2,tau3,tau4,tau5,tau6\n");
  const std::string robot = quoted_source("robots/kr150.yaml");
  const std::string data = " --data " + quoted(dir / "data.csv");

  CliRun run = modelid("fit --method ml --approach 3 --robot " + robot + data);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--method ml needs --periodic"), std::string::npos) << run.err;

  run = modelid("fit --method ml --approach 3 --robot kr150 --periodic" + data);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("needs --robot to be a description file"), std::string::npos) << run.err;

  run = modelid("fit --method ml --approach 4 --robot " + robot + " --periodic" + data);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--approach must be 1, 2, 3 or all, not '4'"), std::string::npos)
      << run.err;

  run = modelid("fit --method ml --robot " + robot + " --periodic" + data);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--method ml needs --approach"), std::string::npos) << run.err;

  run = modelid("fit --method ml --approach 3 --unknown load,Jm --robot " + robot + " --periodic" +
                data);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--unknown takes a comma-separated list of load, Rv, Rc, Rz, not 'Jm'"),
            std::string::npos)
      << run.err;

  // The message points at the key: column 12 is the opening quote of "Ia3".
  write_text(dir / "known.json", "{\"JM3\": 8, \"Ia3\": 8}");
  run = modelid("fit --method ml --approach 3 --robot " + robot + " --periodic --known " +
                quoted(dir / "known.json") + data);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("known.json:1:12: error: 'Ia3' is not a parameter of the drive model"),
            std::string::npos)
      << run.err;

  run = modelid("fit --method mle --robot " + robot + data);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--method must be ols, wls, pim-wls, iv, didim, pm, ml or ml-eiv, not 'mle'"), std::string::npos)
      << run.err;

  run = modelid("fit --method wls --approach 3 --robot " + robot + data);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--approach belongs to --method ml"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace modelgen::test
