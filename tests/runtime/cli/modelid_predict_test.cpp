// modelid predict as a user runs it, against independent computations: the torques it predicts
// are those of the recursive Newton-Euler reference on the standard parameters (computed here,
// in-process); its error table and relative error norm are those of the measured minus the
// reference torques; an estimate of another model is refused without touching the output;
// --plot writes the torques of every experiment (and SVGs when gnuplot is installed).

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include <gtest/gtest.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/io/experiment/trajectory_csv.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/reference_dynamics.hpp"
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

constexpr int kDof = 6;

// TX-40 link inertias and drive values (illustrative magnitudes, every link a possible body:
// simulate refuses others), by standard parameter name.
const std::map<std::string, double> kTruth = {
    {"XX1", 0.8},     {"YY1", 0.8},  {"ZZ1", 1.2},   {"M1", 20},    {"XX2", 0.3},   {"YY2", 0.9},
    {"ZZ2", 1.1},     {"MX2", 2.2},  {"MY2", 0.1},   {"M2", 10},    {"XX3", 0.2},   {"YY3", 0.2},
    {"ZZ3", 0.2},     {"MY3", -0.6}, {"M3", 5},      {"XX4", 0.02}, {"YY4", 0.03},  {"ZZ4", 0.03},
    {"MX4", -0.04},   {"M4", 2},     {"XX5", 0.01},  {"YY5", 0.01}, {"ZZ5", 0.01},  {"YZ5", 0.003},
    {"MY5", 0.02},    {"M5", 1},     {"XX6", 0.002}, {"YY6", 0.002}, {"ZZ6", 0.002}, {"MX6", 0.02},
    {"M6", 0.5},      {"Ia3", 0.09}, {"Ia4", 0.03},  {"Ia5", 0.05}, {"Ia6", 0.01},  {"Fv1", 8},
    {"Fc1", 7},       {"Fv2", 5.5},  {"Fc2", 8},     {"Fv3", 2},    {"Fc3", 6},     {"Fv4", 1.1},
    {"Fc4", 2.5},     {"Fv5", 1.9},  {"Fc5", 3},     {"Fv6", 0.65}, {"Fc6", 0.3},   {"Iam6", 0.0096},
    {"Fvm6", 0.6},    {"Fcm6", 1.9}};

std::string standard_json(const std::map<std::string, double>& parameters) {
  std::ostringstream out;
  out.precision(17);
  out << "{\"standard\": {";
  const char* separator = "";
  for (const auto& [name, value] : parameters) {
    out << separator << "\"" << name << "\": " << value;
    separator = ", ";
  }
  out << "}}\n";
  return out.str();
}

// The numeric reference of the TX-40 description with its standard parameter vector.
struct Reference {
  ReferenceDynamics dynamics;
  Reference() : dynamics(modelgen::load_robot(test::source_path("robots/tx40.yaml")).tree) {}

  Eigen::VectorXd parameters(const std::map<std::string, double>& named) const {
    Eigen::VectorXd p = Eigen::VectorXd::Zero(dynamics.num_params());
    for (const auto& [name, value] : named) {
      bool found = false;
      for (int k = 0; k < dynamics.num_params(); ++k) {
        if (dynamics.tree().params[k].name == name) p[k] = value, found = true;
      }
      EXPECT_TRUE(found) << name;
    }
    return p;
  }
  // Torques of every sample of `x`, samples x dof.
  Eigen::MatrixXd torques(const Trajectory& x, const Eigen::VectorXd& p) const {
    Eigen::MatrixXd tau(x.t.size(), kDof);
    for (Eigen::Index s = 0; s < x.t.size(); ++s) {
      tau.row(s) = dynamics
                       .inverse_dynamics(x.q.row(s).transpose(), x.dq.row(s).transpose(),
                                         x.ddq.row(s).transpose(), p)
                       .transpose();
    }
    return tau;
  }
};

// Noise-free data of the TX-40 made through its description (the numeric reference), so that
// predict's compiled-in model and the data come from different code.
fs::path simulate(const fs::path& dir, const std::string& name, const std::string& sample_time) {
  const fs::path truth = dir / "truth.json", csv = dir / name;
  test::write_text(truth, standard_json(kTruth));
  const CliRun run = modelid("simulate --robot " + quoted_source("robots/tx40.yaml") +
                             " --params " + quoted(truth) + " --trajectory " +
                             quoted_source("robots/data/kr150/excitation.yaml") +
                             " --noise 0 --sample-time " + sample_time + " -o " + quoted(csv));
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return csv;
}

struct ErrorTable {
  std::vector<double> rms_torque, rms_error, percent;
  double rel_error_norm = NAN;
};

// The per-axis table and the relative error norm predict prints.
ErrorTable parse_errors(const std::string& out) {
  ErrorTable table;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line) && line.rfind("  axis", 0) != 0) {
  }
  for (int j = 0; j < kDof && std::getline(in, line); ++j) {
    std::istringstream row(line);
    double axis = 0, torque = 0, error = 0, percent = 0;
    row >> axis >> torque >> error >> percent;
    EXPECT_EQ(axis, j + 1) << line;
    table.rms_torque.push_back(torque);
    table.rms_error.push_back(error);
    table.percent.push_back(percent);
  }
  const std::string key = "||tau - tau_pred|| / ||tau||: ";
  const std::size_t at = out.find(key);
  if (at != std::string::npos) table.rel_error_norm = std::stod(out.substr(at + key.size()));
  return table;
}

// t, q and tau of a simulated file, without its dq and ddq: what a controller logs.
fs::path positions_only(const fs::path& from, const fs::path& to) {
  const Trajectory x = read_trajectory_csv(from.string(), kDof);
  std::ostringstream out;
  out.precision(17);
  out << "t";
  for (const char* prefix : {"q", "tau"}) {
    for (int j = 1; j <= kDof; ++j) out << "," << prefix << j;
  }
  out << "\n";
  for (Eigen::Index s = 0; s < x.t.size(); ++s) {
    out << x.t[s];
    for (const Eigen::MatrixXd* m : {&x.q, &x.tau}) {
      for (int j = 0; j < kDof; ++j) out << "," << (*m)(s, j);
    }
    out << "\n";
  }
  test::write_text(to, out.str());
  return to;
}

TEST(ModelidPredict, UsesTheFitsDataOptionsAndPredictsEverySample) {
  const fs::path dir = test::test_folder();
  const fs::path log = positions_only(simulate(dir, "full.csv", "0.002"), dir / "log.csv");
  const fs::path est = dir / "est.json";
  const CliRun fit = modelid("fit --robot tx40 --method ols --bandwidth 1 --data " +
                             quoted(log) + " -o " + quoted(est));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const nlohmann::json estimate = nlohmann::json::parse(test::read_text(est));
  EXPECT_EQ(estimate["data_options"], nlohmann::json({"--bandwidth", "1"}));

  // Without data options: the fit's, said on stderr; one row per input sample.
  const fs::path pred = dir / "pred.csv";
  const std::string predict =
      "predict --robot tx40 --params " + quoted(est) + " --data " + quoted(log);
  const CliRun every = modelid(predict + " -o " + quoted(pred));
  ASSERT_EQ(every.exit_code, 0) << every.err;
  EXPECT_NE(every.err.find("modelid predict: data options from " + est.string() +
                           " (as the fit prepared its data): --bandwidth 1\n"),
            std::string::npos)
      << every.err;
  const test::CsvTable input = test::read_csv(log), rows = test::read_csv(pred);
  ASSERT_EQ(rows.rows.size(), input.rows.size());
  for (std::size_t s = 0; s < rows.rows.size(); ++s) {
    ASSERT_EQ(rows.at(s, "t"), input.at(s, "t")) << s;
    ASSERT_EQ(rows.at(s, "tau3"), input.at(s, "tau3")) << s;  // as measured, not filtered
  }
  // Noise-free data: the filtered positions' derivatives are close to the exact ones, also
  // within the filter's edges.
  EXPECT_LT(parse_errors(every.out).rel_error_norm, 0.02) << every.out;

  // --decimated: the fit's own comparison, the same samples and relative error norm.
  const CliRun decimated = modelid(predict + " --decimated");
  ASSERT_EQ(decimated.exit_code, 0) << decimated.err;
  EXPECT_NE(decimated.out.find(", " + std::to_string(estimate["samples"].get<long long>()) +
                               " samples,"),
            std::string::npos)
      << decimated.out;
  EXPECT_NEAR(parse_errors(decimated.out).rel_error_norm,
              estimate["rel_error_norm"].get<double>(),
              1e-5 + 1e-4 * estimate["rel_error_norm"].get<double>());

  // Data options on predict's command line win, and stderr says what the fit had.
  const CliRun own = modelid(predict + " --bandwidth 2");
  ASSERT_EQ(own.exit_code, 0) << own.err;
  EXPECT_NE(own.err.find("modelid predict: data options from the command line (--bandwidth 2); "
                         "the fit's, in " + est.string() + ", were --bandwidth 1\n"),
            std::string::npos)
      << own.err;
  EXPECT_NE(own.out.find("excitation bandwidth 2 Hz (given)"), std::string::npos) << own.out;
}

TEST(ModelidPredict, TrueParametersGiveTheReferenceTorquesAndNoError) {
  const fs::path dir = test::test_folder();
  const fs::path csv = simulate(dir, "a.csv", "0.02"), pred = dir / "pred.csv";
  const CliRun run = modelid("predict --robot tx40 --params " + quoted(dir / "truth.json") +
                             " --data " + quoted(csv) + " -o " + quoted(pred));
  ASSERT_EQ(run.exit_code, 0) << run.err;

  const Trajectory data = read_trajectory_csv(csv.string(), kDof);
  const Reference reference;
  const Eigen::MatrixXd tau_reference = reference.torques(data, reference.parameters(kTruth));
  const double scale = data.tau.cwiseAbs().maxCoeff();
  const test::CsvTable table = test::read_csv(pred);
  EXPECT_EQ(table.header, test::expected_header({"q", "tau", "tau_pred", "error"}, kDof));
  ASSERT_EQ(table.rows.size(), static_cast<std::size_t>(data.t.size()));
  double largest_error = 0;
  for (std::size_t s = 0; s < table.rows.size(); ++s) {
    EXPECT_EQ(table.at(s, "experiment"), 1);
    EXPECT_EQ(table.at(s, "t"), data.t[s]);
    for (int j = 0; j < kDof; ++j) {
      const std::string k = std::to_string(j + 1);
      EXPECT_EQ(table.at(s, "q" + k), data.q(s, j));
      EXPECT_EQ(table.at(s, "tau" + k), data.tau(s, j));
      EXPECT_NEAR(table.at(s, "tau_pred" + k), tau_reference(s, j), 1e-10 * scale) << s << " " << k;
      EXPECT_NEAR(table.at(s, "error" + k), data.tau(s, j) - table.at(s, "tau_pred" + k),
                  1e-14 * scale);
      largest_error = std::max(largest_error, std::abs(table.at(s, "error" + k)));
    }
  }
  EXPECT_LT(largest_error, 1e-10 * scale);
  const ErrorTable errors = parse_errors(run.out);
  ASSERT_EQ(errors.rms_error.size(), static_cast<std::size_t>(kDof)) << run.out;
  for (int j = 0; j < kDof; ++j) EXPECT_LT(errors.rms_error[j], 1e-10 * scale) << run.out;
  EXPECT_LT(errors.rel_error_norm, 1e-12) << run.out;
}

TEST(ModelidPredict, PerturbedParametersGiveTheErrorsOfTheReference) {
  const fs::path dir = test::test_folder();
  const fs::path csv = simulate(dir, "a.csv", "0.02");
  const Trajectory data = read_trajectory_csv(csv.string(), kDof);
  const Reference reference;

  // Every parameter 1% larger: the torques are linear in the parameters, so each axis is off by
  // exactly 1% of its torque and the relative error norm is 0.01.
  std::map<std::string, double> scaled = kTruth;
  for (auto& [name, value] : scaled) value *= 1.01;
  test::write_text(dir / "scaled.json", standard_json(scaled));
  const CliRun uniform = modelid("predict --robot tx40 --params " + quoted(dir / "scaled.json") +
                                 " --data " + quoted(csv));
  ASSERT_EQ(uniform.exit_code, 0) << uniform.err;
  const ErrorTable uniform_errors = parse_errors(uniform.out);
  ASSERT_EQ(uniform_errors.percent.size(), static_cast<std::size_t>(kDof)) << uniform.out;
  for (int j = 0; j < kDof; ++j) {
    const double rms_torque = std::sqrt(data.tau.col(j).squaredNorm() / data.t.size());
    EXPECT_NEAR(uniform_errors.rms_torque[j], rms_torque, 1e-5 * rms_torque) << uniform.out;
    EXPECT_NEAR(uniform_errors.rms_error[j], 0.01 * rms_torque, 1e-5 * rms_torque);
    EXPECT_NEAR(uniform_errors.percent[j], 1.0, 1e-3);
  }
  EXPECT_NEAR(uniform_errors.rel_error_norm, 0.01, 1e-7);

  // Parameters 1% off in alternating directions: the errors are those of the reference torques
  // computed here with the same perturbation.
  std::map<std::string, double> perturbed = kTruth;
  double sign = 1;
  for (auto& [name, value] : perturbed) value *= 1 + 0.01 * (sign = -sign);
  test::write_text(dir / "perturbed.json", standard_json(perturbed));
  const fs::path pred = dir / "pred.csv";
  const CliRun run = modelid("predict --robot tx40 --params " + quoted(dir / "perturbed.json") +
                             " --data " + quoted(csv) + " -o " + quoted(pred));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Eigen::MatrixXd expected = reference.torques(data, reference.parameters(perturbed));
  const Eigen::MatrixXd error = data.tau - expected;
  const ErrorTable errors = parse_errors(run.out);
  ASSERT_EQ(errors.percent.size(), static_cast<std::size_t>(kDof)) << run.out;
  for (int j = 0; j < kDof; ++j) {
    const double rms_error = std::sqrt(error.col(j).squaredNorm() / data.t.size());
    const double rms_torque = std::sqrt(data.tau.col(j).squaredNorm() / data.t.size());
    EXPECT_NEAR(errors.rms_error[j], rms_error, 1e-5 * rms_error) << run.out;
    EXPECT_NEAR(errors.percent[j], 100 * rms_error / rms_torque,
                1e-3 * 100 * rms_error / rms_torque);
  }
  const double rel_error_norm = error.norm() / data.tau.norm();
  EXPECT_GT(rel_error_norm, 1e-3);  // a larger error than the true parameters' ~1e-15
  EXPECT_NEAR(errors.rel_error_norm, rel_error_norm, 1e-5 * rel_error_norm) << run.out;
  const test::CsvTable table = test::read_csv(pred);
  ASSERT_EQ(table.rows.size(), static_cast<std::size_t>(data.t.size()));
  const double scale = data.tau.cwiseAbs().maxCoeff();
  for (std::size_t s = 0; s < table.rows.size(); s += 7) {
    for (int j = 0; j < kDof; ++j) {
      const std::string k = std::to_string(j + 1);
      EXPECT_NEAR(table.at(s, "tau_pred" + k), expected(s, j), 1e-10 * scale);
      EXPECT_NEAR(table.at(s, "error" + k), error(s, j), 1e-10 * scale);  // measured - predicted
    }
  }
}

TEST(ModelidPredict, AnEstimateOfAnotherModelIsRefusedAndTheOutputKept) {
  const fs::path dir = test::test_folder();
  const fs::path csv = simulate(dir, "a.csv", "0.02"), pred = dir / "pred.csv";
  test::write_text(pred, "the user's earlier prediction\n");

  // A real estimate of the KR150 (same number of joints) given with the TX-40.
  const fs::path kr150 = dir / "kr150.json";
  const CliRun fit =
      modelid("fit --robot kr150 --data " + quoted_source("robots/data/kr150/excitation.csv") +
              " --method ols -o " + quoted(kr150));
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const CliRun refused = modelid("predict --robot tx40 --params " + quoted(kr150) + " --data " +
                                 quoted(csv) + " -o " + quoted(pred));
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find(kr150.string() + ": error: the estimate belongs to another model: "
                                              "it was identified on 'kr150'"),
            std::string::npos)
      << refused.err;

  // A hand-made estimate naming the TX-40 with a description hash that is not its own.
  const fs::path forged = dir / "forged.json";
  test::write_text(forged, R"({"model": "tx40", "description_sha256": ")" + std::string(64, '0') +
                               R"(", "parameters": [{"name": "ZZ1R", "value": 1}]})");
  const CliRun forged_run = modelid("predict --robot tx40 --params " + quoted(forged) + " --data " +
                                    quoted(csv) + " -o " + quoted(pred));
  EXPECT_EQ(forged_run.exit_code, 1);
  EXPECT_NE(forged_run.err.find("description_sha256 '" + std::string(64, '0') + "'"),
            std::string::npos)
      << forged_run.err;

  EXPECT_EQ(test::read_text(pred), "the user's earlier prediction\n");
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path().filename());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"a.csv", "forged.json", "kr150.json", "pred.csv",
                                             "truth.json"}));

  // Without a hash (hand-written parameters) or with an empty one, the estimate is used.
  test::write_text(forged, R"({"description_sha256": "", "base": {"ZZ1R": 1}})");
  EXPECT_EQ(modelid("predict --robot tx40 --params " + quoted(forged) + " --data " + quoted(csv))
                .exit_code,
            0);
}

TEST(ModelidPredict, AnEstimateOfTheSameDescriptionIsAccepted) {
  // fit through the compiled-in model, predict through the description it was generated from:
  // both carry the SHA-256 of robots/tx40.yaml.
  const fs::path dir = test::test_folder();
  const fs::path csv = simulate(dir, "a.csv", "0.01"), estimate = dir / "est.json";
  ASSERT_EQ(
      modelid("fit --robot tx40 --method ols --data " + quoted(csv) + " -o " + quoted(estimate))
          .exit_code,
      0);
  const CliRun run = modelid("predict --robot " + quoted_source("robots/tx40.yaml") + " --params " +
                             quoted(estimate) + " --data " + quoted(csv));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_LT(parse_errors(run.out).rel_error_norm, 1e-9) << run.out;
}

// Without measured torques predict still predicts: the CSV holds the positions and the
// predicted torques, which are the reference's.
TEST(ModelidPredict, DataWithoutTorquesGivePredictionsOnly) {
  const fs::path dir = test::test_folder();
  const fs::path csv = simulate(dir, "a.csv", "0.05"), pred = dir / "pred.csv";
  // The same file without its tau columns.
  const test::CsvTable full = test::read_csv(csv);
  std::string text = "t";
  for (const char* prefix : {"q", "dq", "ddq"}) {
    for (int j = 1; j <= kDof; ++j) text += "," + std::string(prefix) + std::to_string(j);
  }
  text += "\n";
  for (std::size_t s = 0; s < full.rows.size(); ++s) {
    std::ostringstream row;
    row.precision(17);
    row << full.at(s, "t");
    for (const char* prefix : {"q", "dq", "ddq"}) {
      for (int j = 1; j <= kDof; ++j) row << "," << full.at(s, prefix + std::to_string(j));
    }
    text += row.str() + "\n";
  }
  test::write_text(dir / "positions.csv", text);
  const CliRun run = modelid("predict --robot tx40 --params " + quoted(dir / "truth.json") +
                             " --data " + quoted(dir / "positions.csv") + " -o " + quoted(pred));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("predicted torques only"), std::string::npos) << run.out;
  const Trajectory data = read_trajectory_csv(csv.string(), kDof);
  const Reference reference;
  const Eigen::MatrixXd tau_reference = reference.torques(data, reference.parameters(kTruth));
  const double scale = data.tau.cwiseAbs().maxCoeff();
  const test::CsvTable table = test::read_csv(pred);
  EXPECT_EQ(table.header, test::expected_header({"q", "tau_pred"}, kDof));
  ASSERT_EQ(table.rows.size(), static_cast<std::size_t>(data.t.size()));
  for (std::size_t s = 0; s < table.rows.size(); ++s) {
    for (int j = 0; j < kDof; ++j) {
      EXPECT_NEAR(table.at(s, "tau_pred" + std::to_string(j + 1)), tau_reference(s, j),
                  1e-10 * scale);
    }
  }
}

TEST(ModelidPredict, DataProblemsNameTheFile) {
  const fs::path dir = test::test_folder();
  test::write_text(dir / "truth.json", standard_json(kTruth));
  // Files with torques and files without cannot be mixed: the comparison would be partial.
  const fs::path with_tau = simulate(dir, "a.csv", "0.05");
  test::write_text(
      dir / "no_tau.csv",
      "t,q1,q2,q3,q4,q5,q6,dq1,dq2,dq3,dq4,dq5,dq6,ddq1,ddq2,ddq3,ddq4,ddq5,ddq6\n"
      "0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n0.1,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n"
      "0.2,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n");
  const CliRun mixed =
      modelid("predict --robot tx40 --params " + quoted(dir / "truth.json") + " --data " +
              quoted(with_tau) + " --data " + quoted(dir / "no_tau.csv"));
  EXPECT_EQ(mixed.exit_code, 1);
  EXPECT_NE(mixed.err.find((dir / "no_tau.csv").string() + ": error: no torque or current "
                                                           "columns"),
            std::string::npos)
      << mixed.err;
  const CliRun nan =
      modelid("predict --robot kr150 --params " + quoted_source("robots/data/kr150/true.json") +
              " --data " + quoted_source("tests/bad_inputs/data/nan_value.csv"));
  EXPECT_EQ(nan.exit_code, 1);
  EXPECT_NE(nan.err.find("nan_value.csv"), std::string::npos) << nan.err;
  // -o into a folder that does not exist: a clear error, nothing written.
  const CliRun unwritable = modelid("predict --robot tx40 --params " + quoted(dir / "truth.json") +
                                    " --data " + quoted(simulate(dir, "a.csv", "0.05")) + " -o " +
                                    quoted(dir / "missing" / "pred.csv"));
  EXPECT_EQ(unwritable.exit_code, 1);
  EXPECT_NE(unwritable.err.find("pred.csv: error: cannot write the file"), std::string::npos)
      << unwritable.err;
}

TEST(ModelidPredict, PlotWritesTheTorquesOfEveryExperiment) {
  const fs::path dir = test::test_folder();
  const fs::path a = simulate(dir, "a.csv", "0.02"), b = simulate(dir, "b.csv", "0.05");
  const fs::path plots = dir / "plots" / "run1";  // parents made as needed
  const CliRun run =
      modelid("predict --robot tx40 --params " + quoted(dir / "truth.json") + " --data " +
              quoted(a) + " --data " + quoted(b) + " --plot " + quoted(plots));
  ASSERT_EQ(run.exit_code, 0) << run.err;

  const std::vector<Trajectory> data = {read_trajectory_csv(a.string(), kDof),
                                        read_trajectory_csv(b.string(), kDof)};
  const Reference reference;
  const Eigen::VectorXd p = reference.parameters(kTruth);
  const test::CsvTable table = test::read_csv(plots / "torques.csv");
  EXPECT_EQ(table.header, test::expected_header({"tau", "tau_pred", "error"}, kDof));
  ASSERT_EQ(table.rows.size(), static_cast<std::size_t>(data[0].t.size() + data[1].t.size()));
  std::size_t row = 0;
  for (std::size_t e = 0; e < data.size(); ++e) {
    const Eigen::MatrixXd tau = reference.torques(data[e], p);
    const double scale = data[e].tau.cwiseAbs().maxCoeff();
    for (Eigen::Index s = 0; s < data[e].t.size(); ++s, ++row) {
      EXPECT_EQ(table.at(row, "experiment"), static_cast<double>(e + 1));
      EXPECT_EQ(table.at(row, "t"), data[e].t[s]);
      for (int j = 0; j < kDof; ++j) {
        const std::string k = std::to_string(j + 1);
        EXPECT_EQ(table.at(row, "tau" + k), data[e].tau(s, j));
        EXPECT_NEAR(table.at(row, "tau_pred" + k), tau(s, j), 1e-10 * scale);
      }
    }
  }
  EXPECT_TRUE(fs::exists(plots / "plot.gp"));
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    for (int j = 1; j <= kDof; ++j) {
      const std::string svg = test::read_text(plots / ("axis" + std::to_string(j) + ".svg"));
      EXPECT_NE(svg.find("<svg"), std::string::npos) << "axis" << j;
      EXPECT_NE(svg.find("</svg>"), std::string::npos) << "axis" << j;
    }
    EXPECT_EQ(run.err.find("warning"), std::string::npos) << run.err;
  } else {
    EXPECT_NE(run.out.find("axis SVGs skipped: gnuplot is not on PATH"), std::string::npos)
        << run.out;
    EXPECT_FALSE(fs::exists(plots / "axis1.svg"));
  }

  // A file where the folder should be: exit 1 before any work.
  test::write_text(dir / "file", "");
  const CliRun not_a_folder =
      modelid("predict --robot tx40 --params " + quoted(dir / "truth.json") + " --data " +
              quoted(a) + " --plot " + quoted(dir / "file"));
  EXPECT_EQ(not_a_folder.exit_code, 1);
  EXPECT_NE(not_a_folder.err.find("error:"), std::string::npos) << not_a_folder.err;
}

}  // namespace
}  // namespace modelgen
