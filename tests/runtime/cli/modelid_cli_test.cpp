// modelid as a user runs it: the bundled KR150 data are exactly what the documented simulate
// command makes; fitting noise-free simulated data gives the true base parameters; bad data
// and unknown robots give messages and exit 1; command lines that cannot be right exit 2;
// --version prints modelgen's version; short runs print no progress lines into logs. predict:
// modelid_predict_test.cpp; fit's essential parameters and plots: modelid_fit_test.cpp.

#include <sys/resource.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/runtime/cli/modelid_cli_support.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using test::CliRun;
using test::modelid;
using test::read_text;

std::string quoted(const std::string& relative) { return test::quoted_source(relative); }

std::string read(const std::string& path) { return read_text(path); }

// A fit that fails on its data must not leave the --plot folder it was asked to make.
TEST(ModelidCli, AFailedFitCreatesNoPlotFolder) {
  const std::filesystem::path dir = test::test_folder();
  const std::filesystem::path plots = dir / "new" / "plots";
  const CliRun run = modelid("fit --robot tests/bad_inputs/robots/two_axes.yaml --data " +
                                 test::quoted_source("tests/bad_inputs/data/nan_value.csv") +
                                 " --method ols --plot " + test::quoted(plots),
                             {MODELGEN_SOURCE_DIR});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "new")) << "a failed fit made the plot folder";

  // A folder that can never be made still fails before any work.
  test::write_text(dir / "file", "");
  const CliRun under_a_file = modelid("fit --robot tx40 --data x.csv --method ols --plot " +
                                      test::quoted(dir / "file" / "plots"));
  EXPECT_EQ(under_a_file.exit_code, 1);
  EXPECT_NE(under_a_file.err.find("cannot create the plot folder"), std::string::npos)
      << under_a_file.err;
}

// A write that the system refuses (a full disk: ENOSPC; here a file size limit: EFBIG) says
// why, leaves the old output and no temporary.
TEST(ModelidCli, AFailedWriteGivesTheSystemsReason) {
  const std::filesystem::path dir = test::test_folder();
  const std::filesystem::path out = dir / "simulated.csv";
  test::write_text(out, "the user's earlier data\n");
  // Inherited by the shell and modelid: no SIGXFSZ kill, writes beyond 8 kB fail with EFBIG.
  rlimit before{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &before), 0);
  const rlimit limit{8192, before.rlim_max};
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limit), 0);
  const CliRun run = modelid(
      "simulate --robot tests/bad_inputs/robots/two_axes.yaml --params "
      "tests/bad_inputs/robots/two_axes_params.json --trajectory "
      "tests/bad_inputs/robots/two_axes_trajectory.yaml --noise 0 -o " + test::quoted(out),
      {MODELGEN_SOURCE_DIR});
  ::setrlimit(RLIMIT_FSIZE, &before);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("cannot write the file: " + std::string(std::strerror(EFBIG))),
            std::string::npos)
      << run.err;
  EXPECT_EQ(read_text(out), "the user's earlier data\n");
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 1u) << "a temporary was left beside the output";
}

TEST(ModelidCli, BundledDataComeFromTheDocumentedSimulation) {
  const std::string csv = testing::TempDir() + "kr150_resimulated.csv";
  const CliRun run =
      modelid("simulate --robot kr150 --params " + quoted("robots/data/kr150/true.json") +
              " --trajectory " + quoted("robots/data/kr150/excitation.yaml") +
              " --noise 2 --seed 1 --sample-time 0.01 -o '" + csv + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(read(csv), read(test::source_path("robots/data/kr150/excitation.csv")))
      << "robots/data/kr150/excitation.csv is not what its documented command makes";
}

TEST(ModelidCli, NoiseFreeDataGiveTheTrueParameters) {
  const std::string csv = testing::TempDir() + "tx40_noise_free.csv";
  const std::string estimate = testing::TempDir() + "tx40_noise_free.json";
  const std::string truth = testing::TempDir() + "tx40_truth.json";
  // TX-40 with its own description's a-priori drive values plus link inertias, through the
  // numeric reference (--robot is the description file).
  std::ofstream(truth) << R"({"standard": {"XX1": 0.8, "YY1": 0.8, "ZZ1": 1.2, "M1": 20,
      "XX2": 0.3, "YY2": 0.9, "ZZ2": 1.1, "MX2": 2.2, "MY2": 0.1, "M2": 10, "XX3": 0.2,
      "YY3": 0.2, "ZZ3": 0.2, "MY3": -0.6, "M3": 5, "XX4": 0.02, "YY4": 0.03, "ZZ4": 0.03,
      "MX4": -0.04, "M4": 2, "XX5": 0.01, "YY5": 0.01, "ZZ5": 0.01, "YZ5": 0.003, "MY5": 0.02,
      "M5": 1, "XX6": 0.002, "YY6": 0.002, "ZZ6": 0.002, "MX6": 0.02, "M6": 0.5, "Ia3": 0.09, "Ia4": 0.03, "Ia5": 0.05, "Ia6": 0.01,
      "Fv1": 8, "Fc1": 7, "Fv2": 5.5, "Fc2": 8, "Fv3": 2, "Fc3": 6, "Fv4": 1.1, "Fc4": 2.5,
      "Fv5": 1.9, "Fc5": 3, "Fv6": 0.65, "Fc6": 0.3, "Iam6": 0.0096, "Fvm6": 0.6, "Fcm6": 1.9}})";
  const std::string description = quoted("robots/tx40.yaml");
  ASSERT_EQ(modelid("simulate --robot " + description + " --params '" + truth + "' --trajectory " +
                    quoted("robots/data/kr150/excitation.yaml") + " --noise 0 -o '" + csv + "'")
                .exit_code,
            0);
  const CliRun fit = modelid("fit --robot tx40 --data '" + csv + "' --method ols -o '" + estimate +
                             "' --truth '" + truth + "'");
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const nlohmann::json json = nlohmann::json::parse(read(estimate));
  EXPECT_EQ(json["model"], "tx40");
  EXPECT_EQ(json["description_sha256"].get<std::string>().size(), 64u);
  EXPECT_LT(json["rel_error_norm"].get<double>(), 1e-10);
  // The compiled-in model and the reference agree, so the truth read through the compiled-in
  // model's regrouping is what the fit must return.
  const CliRun truth_fit = modelid("fit --robot " + description + " --data '" + csv +
                                   "' --method ols -o '" + estimate + ".ref'");
  ASSERT_EQ(truth_fit.exit_code, 0) << truth_fit.err;
  const nlohmann::json reference = nlohmann::json::parse(read(estimate + ".ref"));
  ASSERT_EQ(json["parameters"].size(), reference["parameters"].size());
  for (std::size_t b = 0; b < json["parameters"].size(); ++b) {
    const double a = json["parameters"][b]["value"], r = reference["parameters"][b]["value"];
    EXPECT_NEAR(a, r, 1e-8 * std::max(1.0, std::abs(r))) << json["parameters"][b]["name"];
  }
  // Against the truth itself (--truth puts it beside each estimate).
  for (const auto& parameter : json["parameters"]) {
    const double value = parameter["value"], truth_value = parameter["truth"];
    EXPECT_NEAR(value, truth_value, 1e-8 * std::max(1.0, std::abs(truth_value)))
        << parameter["name"];
  }
  EXPECT_EQ(json["parameters"].size(), 61u);
}

TEST(ModelidCli, BadDataAndUnknownRobotExitOne) {
  const CliRun bad = modelid("fit --robot tx40 --data " +
                             quoted("tests/bad_inputs/data/nan_value.csv") + " --method wls");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("missing column 'q3'"), std::string::npos) << bad.err;
  const CliRun unknown = modelid("fit --robot kr15 --data x.csv --method wls");
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.err.find("compiled in:"), std::string::npos) << unknown.err;
  const CliRun usage = modelid("fit --robot tx40 --bogus 1");
  EXPECT_EQ(usage.exit_code, 2);
}

TEST(ModelidCli, CommandLinesThatCannotBeRightExitTwo) {
  const std::string data = " --data " + quoted("robots/data/kr150/excitation.csv");
  struct Case {
    std::string arguments, message;
  };
  const std::vector<Case> cases = {
      {"fit --robot kr150 --method ols --essential --r-sigma 0.5" + data, "--r-sigma must be"},
      {"fit --robot kr150 --method ols --r-sigma 5" + data, "add --essential"},
      {"fit --robot kr150 --method ols --essential --essential" + data, "--essential given twice"},
      {"fit --robot kr150 --method ols --essential" + data + " --r-sigma",
       "--r-sigma needs a value"},
      {"predict --robot kr150" + data, "predict needs --params"},
      {"predict --robot kr150 --params x.json", "predict needs --data"},
      {"predict --robot kr150 --params x.json --truth y.json" + data, "unknown option '--truth'"},
      {"frobnicate", "unknown command 'frobnicate'"},
  };
  for (const Case& c : cases) {
    const CliRun run = modelid(c.arguments);
    EXPECT_EQ(run.exit_code, 2) << c.arguments << "\n" << run.err;
    EXPECT_NE(run.err.find(c.message), std::string::npos) << c.arguments << "\n" << run.err;
    // The command's own usage follows the message; the program's for an unknown command.
    const std::string command = c.arguments.substr(0, c.arguments.find(' '));
    const bool known = command == "fit" || command == "predict";
    EXPECT_NE(run.err.find("usage: modelid " + (known ? command : std::string("fit"))),
              std::string::npos)
        << run.err;
  }
}

// Both programs carry the project's version: modelid prints the same one modelgen does, on
// stdout, exit 0, and its usage text names the option.
TEST(ModelidCli, VersionIsTheProjectVersionModelgenPrints) {
  const CliRun generator = test::modelgen("--version");
  ASSERT_EQ(generator.exit_code, 0) << generator.err;
  const std::string prefix = "modelgen ";
  ASSERT_EQ(generator.out.rfind(prefix, 0), 0u) << generator.out;
  const std::string version = generator.out.substr(prefix.size());  // "x.y.z\n"
  ASSERT_GT(version.size(), 1u);
  const CliRun run = modelid("--version");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "modelid " + version);
  EXPECT_EQ(run.err, "");
  const CliRun help = modelid("--help");
  EXPECT_NE(help.out.find("modelid --version"), std::string::npos) << help.out;
}

TEST(ModelidCli, ShortRunsPrintNoProgressIntoLogs) {
  // stderr is a file here, not a terminal: a run shorter than a second adds no progress line,
  // so simulate says only where it wrote.
  const std::filesystem::path dir = test::test_folder();
  const CliRun run =
      modelid("simulate --robot kr150 --params " + quoted("robots/data/kr150/true.json") +
              " --trajectory " + quoted("robots/data/kr150/excitation.yaml") + " --noise 1 -o " +
              test::quoted(dir / "a.csv"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "modelid simulate: 1000 samples of kr150 written to " +
                         (dir / "a.csv").string() + "\n");
  EXPECT_EQ(run.err.find('\r'), std::string::npos);
}

TEST(ModelidCli, ProgressGoesToLogsOnlyWhenAskedFor) {
  // stderr is a file: a fit that prints progress at each quarter when asked (--progress) prints
  // none otherwise, however long it runs.
  const std::string fit = "fit --robot kr150 --method wls --data " +
                          quoted("robots/data/kr150/excitation.csv");
  const CliRun quiet = modelid(fit);
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err.find("modelid: fitting"), std::string::npos) << quiet.err;
  EXPECT_EQ(quiet.err.find("modelid: reading data"), std::string::npos) << quiet.err;
  const CliRun shown = modelid(fit + " --progress");
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  EXPECT_NE(shown.err.find("modelid: fitting 100%\n"), std::string::npos) << shown.err;
  EXPECT_EQ(shown.err.find('\r'), std::string::npos);
  EXPECT_EQ(shown.out, quiet.out);
}

// The two conventions of excitation files: position amplitudes (Swevers 2002 eq. 15, sparse
// terms as in its Table 1) give q = q0 + sum a sin(l w t) + b cos(l w t), computed here in closed
// form; the same trajectory in velocity amplitudes (dense lists) gives the same samples.
TEST(ModelidCli, TrajectoryFormsFollowTheirEquations) {
  const std::filesystem::path dir = test::test_folder();
  const double period = 8.0, w = 2 * M_PI / period;
  // Joint 3: q0 = 0.4, harmonic 3 with a = 0.1, b = -0.05; other joints still.
  std::string position = "period: 8\nform: position\njoints:\n";
  std::string velocity = "period: 8\njoints:\n";
  for (int j = 1; j <= 6; ++j) {
    if (j == 3) {
      position += "  - {q0: 0.4, terms: [{l: 3, a: 0.1, b: -0.05}]}\n";
      // a_v/(3w) = 0.1 and -b_v/(3w) = -0.05.
      velocity += "  - {q0: 0.4, a: [0, 0, " + std::to_string(0.1 * 3 * w) + "], b: [0, 0, " +
                  std::to_string(0.05 * 3 * w) + "]}\n";
    } else {
      position += "  - {q0: 0, terms: []}\n";
      velocity += "  - {q0: 0, a: [0], b: [0]}\n";
    }
  }
  test::write_text(dir / "position.yaml", position);
  test::write_text(dir / "velocity.yaml", velocity);
  test::write_text(dir / "zero.json", "{\"base\": {}}");
  for (const char* name : {"position", "velocity"}) {
    const CliRun run = modelid(
        "simulate --robot tx40 --params " + test::quoted(dir / "zero.json") + " --trajectory " +
        test::quoted(dir / (std::string(name) + ".yaml")) + " --noise 0 --sample-time 0.5 -o " +
        test::quoted(dir / (std::string(name) + ".csv")));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const test::CsvTable table = test::read_csv(dir / (std::string(name) + ".csv"));
    ASSERT_EQ(table.rows.size(), 16u);
    for (std::size_t s = 0; s < table.rows.size(); ++s) {
      const double t = table.at(s, "t");
      EXPECT_NEAR(table.at(s, "q3"), 0.4 + 0.1 * std::sin(3 * w * t) - 0.05 * std::cos(3 * w * t),
                  1e-6)
          << name << " t = " << t;
      EXPECT_NEAR(table.at(s, "dq3"),
                  0.1 * 3 * w * std::cos(3 * w * t) + 0.05 * 3 * w * std::sin(3 * w * t), 1e-6)
          << name;
      EXPECT_EQ(table.at(s, "q1"), 0.0);
    }
  }
  test::write_text(dir / "bad.yaml", "period: 8\nform: amplitude\njoints: []\n");
  const CliRun bad = modelid("simulate --robot tx40 --params " + test::quoted(dir / "zero.json") +
                             " --trajectory " + test::quoted(dir / "bad.yaml") + " --noise 0 -o " +
                             test::quoted(dir / "bad.csv"));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("bad.yaml:2"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace modelgen
