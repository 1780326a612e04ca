// modelid check-trajectory against peaks computed by hand: a single harmonic in position form,
// q = q0 + a sin(l wf t) + b cos(l wf t), peaks at q0 +- r, |dq| at r l wf, |ddq| at r (l wf)^2
// with r = hypot(a, b); position use is the distance from the middle of the range over half
// the range.

#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "modelgen/model/number_text.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::test {
namespace {

namespace fs = std::filesystem;

// The whitespace-separated fields of the table row that starts with `joint`.
std::vector<std::string> row_of(const std::string& out, const std::string& joint) {
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(joint + " ", 0) != 0) continue;
    std::istringstream fields(line);
    std::vector<std::string> row;
    for (std::string field; fields >> field;) row.push_back(field);
    return row;
  }
  ADD_FAILURE() << "no row '" << joint << "' in:\n" << out;
  return {};
}

// A "80.0%" field as 0.8.
double fraction(const std::string& field) { return std::stod(field) / 100; }

constexpr const char* kRobot = "tests/bad_inputs/robots/two_axes_limited.yaml";

TEST(ModelidCheckTrajectory, PrintsThePeakUseOfEveryLimit) {
  const fs::path dir = test_folder();
  write_text(dir / "one.yaml",
             "period: 2\nform: position\njoints:\n"
             "  - {q0: 0.2, terms: [{l: 1, a: 0.6, b: 0.8}]}\n"
             "  - {q0: 0.25, terms: [{l: 2, a: 0.1, b: 0}]}\n");
  const CliRun run = modelid("check-trajectory --robot " + quoted_source(kRobot) +
                             " --trajectory " + quoted(dir / "one.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const double pi = std::numbers::pi;
  // Joint 1: r = 1, wf = pi; q in [-0.8, 1.2] against [-1.5, 1.5]; dq limit 7, ddq 20.
  const std::vector<std::string> j1 = row_of(run.out, "1");
  ASSERT_EQ(j1.size(), 11u) << run.out;
  EXPECT_NEAR(std::stod(j1[2]), 1.2, 1e-3);
  EXPECT_NEAR(fraction(j1[4]), 1.2 / 1.5, 1e-3);
  EXPECT_NEAR(std::stod(j1[5]), pi, 1e-3);
  EXPECT_NEAR(fraction(j1[7]), pi / 7, 1e-3);
  EXPECT_NEAR(std::stod(j1[8]), pi * pi, 1e-2);
  EXPECT_NEAR(fraction(j1[10]), pi * pi / 20, 1e-3);
  // Joint 2: r = 0.1, l wf = 2 pi; q in [0.15, 0.35] against [-1, 1.5] (middle 0.25, half
  // range 1.25); dq limit 1.5, ddq 15.
  const std::vector<std::string> j2 = row_of(run.out, "2");
  ASSERT_EQ(j2.size(), 11u) << run.out;
  EXPECT_NEAR(fraction(j2[4]), 0.1 / 1.25, 1e-3);
  EXPECT_NEAR(std::stod(j2[5]), 0.2 * pi, 1e-3);
  EXPECT_NEAR(fraction(j2[7]), 0.2 * pi / 1.5, 1e-3);
  EXPECT_NEAR(std::stod(j2[8]), 0.4 * pi * pi, 1e-3);
  EXPECT_NEAR(fraction(j2[10]), 0.4 * pi * pi / 15, 1e-3);
  EXPECT_EQ(run.out.find('!'), std::string::npos) << run.out;
}

TEST(ModelidCheckTrajectory, ExceededLimitsAreMarkedAndFail) {
  const CliRun run = modelid("check-trajectory --robot " + quoted_source(kRobot) +
                             " --trajectory " +
                             quoted_source("tests/bad_inputs/limits/beyond_velocity.yaml"));
  EXPECT_EQ(run.exit_code, 1);
  const std::vector<std::string> j2 = row_of(run.out, "2");
  ASSERT_EQ(j2.size(), 11u) << run.out;
  EXPECT_EQ(j2[7], "125.7%!");  // 0.6 pi / 1.5
  EXPECT_NE(run.err.find("1 limit is exceeded"), std::string::npos) << run.err;
}

// The most harmonics a trajectory may have, every one of them used: q1 = c sum_{l=1..1000}
// cos(l wf t) peaks at t = 0 with q = 1000 c and |ddq| = c wf^2 sum l^2 = c pi^2 1000 1001 2001 / 6
// (wf = pi), as all its terms do. The limit grid once took 108 s here and 57 s in simulate
// (points times harmonics); a few seconds are plenty even under the sanitizers.
TEST(ModelidCheckTrajectory, AThousandHarmonicsAreCheckedInSeconds) {
  const fs::path dir = test_folder();
  std::string terms;
  for (int l = 1; l <= 1000; ++l) {
    terms += (l > 1 ? ", " : "") + std::string("{l: ") + std::to_string(l) + ", a: 0, b: 1e-4}";
  }
  write_text(dir / "thousand.yaml", "period: 2\nform: position\njoints:\n  - {q0: 0, terms: [" +
                                        terms + "]}\n  - {q0: 0, terms: []}\n");
  const auto seconds_of = [](const auto& run) {
    const auto start = std::chrono::steady_clock::now();
    const CliRun result = run();
    return std::pair{
        result, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
  };
  const auto [check, check_seconds] = seconds_of([&] {
    return modelid("check-trajectory --robot " + quoted_source(kRobot) + " --trajectory " +
                   quoted(dir / "thousand.yaml"));
  });
  EXPECT_EQ(check.exit_code, 1) << check.err;
  EXPECT_LT(check_seconds, 15);
  const std::vector<std::string> j1 = row_of(check.out, "1");
  ASSERT_EQ(j1.size(), 11u) << check.out;
  const double pi = std::numbers::pi;
  EXPECT_NEAR(std::stod(j1[2]), 0.1, 1e-6);
  // The table rounds a value this large to four significant digits.
  const double ddq_peak = 1e-4 * pi * pi * 1000.0 * 1001 * 2001 / 6;
  EXPECT_NEAR(std::stod(j1[8]), ddq_peak, 1e-4 * ddq_peak);
  const auto [simulate, simulate_seconds] = seconds_of([&] {
    return modelid("simulate --robot " + quoted_source(kRobot) + " --params " +
                   quoted_source("tests/bad_inputs/robots/two_axes_params.json") +
                   " --trajectory " + quoted(dir / "thousand.yaml") + " -o " +
                   quoted(dir / "simulated.csv"));
  });
  EXPECT_EQ(simulate.exit_code, 1) << simulate.err;
  EXPECT_NE(simulate.err.find("joint 1 ('J1') leaves its"), std::string::npos) << simulate.err;
  EXPECT_LT(simulate_seconds, 15);
}

TEST(ModelidCheckTrajectory, NamesTheLimitsTheDescriptionLacks) {
  // two_axes.yaml has no limits at all: every key is named, joint by joint, and nothing fails.
  const CliRun run = modelid("check-trajectory --robot " +
                             quoted_source("tests/bad_inputs/robots/two_axes.yaml") +
                             " --trajectory " +
                             quoted_source("tests/bad_inputs/limits/beyond_velocity.yaml"));
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("no 'dq' limit for joint 1 ('J1'), joint 2 ('J2'); not checked"),
            std::string::npos)
      << run.err;
}

// The rows of the a-priori torque table: what follows its heading.
std::string torque_table(const std::string& out) {
  const auto at = out.find("a-priori joint torques");
  if (at == std::string::npos) ADD_FAILURE() << "no torque table in:\n" << out;
  return at == std::string::npos ? "" : out.substr(at);
}

constexpr const char* kEffortRobot = "tests/bad_inputs/robots/two_axes_effort.yaml";

// Joint 1 alone moves, q1 = r sin(pi t + phase) (period 2 s), joint 2 held at 0; from the
// closed form in two_axes_effort.yaml, |tau1| peaks at 0.75 r pi^2 and |tau2| at 0.05 r pi^2,
// against the effort limits 4 and 0.3 N m there.
std::string joint1_swing(double a, double b) {
  return "period: 2\nform: position\njoints:\n  - {q0: 0, terms: [{l: 1, a: " + shortest_text(a) +
         ", b: " + shortest_text(b) + "}]}\n  - {q0: 0, terms: []}\n";
}

TEST(ModelidCheckTrajectory, PrintsThePeakAPrioriTorqueAgainstTheEffortLimit) {
  const fs::path dir = test_folder();
  write_text(dir / "within.yaml", joint1_swing(0.24, 0.32));  // r = 0.4
  const CliRun run = modelid("check-trajectory --robot " + quoted_source(kEffortRobot) +
                             " --trajectory " + quoted(dir / "within.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const double pi2 = std::numbers::pi * std::numbers::pi;
  const std::string table = torque_table(run.out);
  const std::vector<std::string> j1 = row_of(table, "1"), j2 = row_of(table, "2");
  ASSERT_EQ(j1.size(), 6u) << table;  // 1 J1 peak time effort use
  EXPECT_NEAR(std::stod(j1[2]), 0.75 * 0.4 * pi2, 1e-3);
  EXPECT_EQ(std::stod(j1[4]), 4);
  EXPECT_NEAR(fraction(j1[5]), 0.75 * 0.4 * pi2 / 4, 1e-3);
  ASSERT_EQ(j2.size(), 6u) << table;
  EXPECT_NEAR(std::stod(j2[2]), 0.05 * 0.4 * pi2, 1e-4);
  EXPECT_NEAR(fraction(j2[5]), 0.05 * 0.4 * pi2 / 0.3, 1e-3);
  EXPECT_EQ(run.out.find('!'), std::string::npos) << run.out;

  write_text(dir / "beyond.yaml", joint1_swing(0.6, 0));  // tau1 = 0.45 pi^2 = 4.44 > 4
  const CliRun beyond = modelid("check-trajectory --robot " + quoted_source(kEffortRobot) +
                                " --trajectory " + quoted(dir / "beyond.yaml"));
  EXPECT_EQ(beyond.exit_code, 1);
  const std::vector<std::string> over = row_of(torque_table(beyond.out), "1");
  ASSERT_EQ(over.size(), 6u) << beyond.out;
  EXPECT_EQ(over[5], "111.0%!");  // 0.45 pi^2 / 4 = 1.1103
  EXPECT_NE(beyond.err.find("1 limit is exceeded"), std::string::npos) << beyond.err;
}

TEST(ModelidCheckTrajectory, EffortLimitsWithoutInertialValuesAreNotedOnce) {
  // robots/tx40.yaml gives effort limits and a-priori drive values, but no link inertials.
  const CliRun run = modelid("check-trajectory --robot tx40 --trajectory " +
                             quoted_source("robots/data/tx40/design.yaml"));
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const std::string note =
      "modelid check-trajectory: note: the description gives effort limits but no a-priori "
      "inertial values (XX1 is not given: URDF <inertial>, YAML known:); joint torques are not "
      "checked against them\n";
  EXPECT_EQ(run.err, note);
  EXPECT_EQ(run.out.find("a-priori joint torques"), std::string::npos) << run.out;
}

TEST(ModelidCheckTrajectory, BundledExcitationsAreWithinTheLimits) {
  for (const auto& [robot, trajectory] :
       {std::pair{"kr150", "robots/data/kr150/excitation.yaml"},
        std::pair{"kr150", "robots/data/kr150/load/design.yaml"},
        std::pair{"tx40", "robots/data/tx40/design.yaml"}}) {
    const CliRun run = modelid(std::string("check-trajectory --robot ") + robot +
                               " --trajectory " + quoted_source(trajectory));
    EXPECT_EQ(run.exit_code, 0) << trajectory << "\n" << run.out << run.err;
  }
}

}  // namespace
}  // namespace modelgen::test
