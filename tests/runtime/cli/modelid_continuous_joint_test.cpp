// A URDF `continuous` joint has no position limit (urdfdom drops lower and upper on one):
// check-trajectory and design take it as unbounded in q, while its velocity limit still holds;
// --q-limit JOINT=LO,HI gives it (or any joint) a range.
// The robot: joint 1 'spin' continuous about the vertical (dq limit 2 rad/s), joint 2 'elbow'
// revolute in [-1.5, 1.5] (dq limit 3 rad/s).

#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* kUrdf = R"(<?xml version="1.0"?>
<robot name="spinner">
  <link name="base"/>
  <link name="l1">
    <inertial>
      <origin xyz="0.1 0 0.05"/>
      <mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/>
    </inertial>
  </link>
  <link name="l2">
    <inertial>
      <origin xyz="0.2 0 0"/>
      <mass value="1"/>
      <inertia ixx="0.005" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial>
  </link>
  <joint name="spin" type="continuous">
    <parent link="base"/>
    <child link="l1"/>
    <axis xyz="0 0 1"/>
    <limit velocity="2" effort="50"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="l1"/>
    <child link="l2"/>
    <origin xyz="0.3 0 0" rpy="1.5707963267948966 0 0"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1.5" upper="1.5" velocity="3" effort="20"/>
  </joint>
</robot>
)";

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

// Joint 1 at q0 = 10 rad, far beyond any range, with amplitude `a` at 0.5 Hz: |dq| = a pi.
fs::path write_trajectory(const fs::path& dir, const std::string& a) {
  write_text(dir / "spin.yaml",
             "period: 2\nform: position\njoints:\n"
             "  - {q0: 10, terms: [{l: 1, a: " +
                 a +
                 ", b: 0}]}\n"
                 "  - {q0: 0.2, terms: [{l: 1, a: 0.3, b: 0}]}\n");
  return dir / "spin.yaml";
}

TEST(ModelidContinuousJoint, CheckTrajectoryTakesNoPositionLimit) {
  const fs::path dir = test_folder();
  write_text(dir / "spinner.urdf", kUrdf);
  // |dq| = 0.5 pi = 1.57 of 2: within every limit although q reaches 10.5 rad.
  const CliRun run = modelid("check-trajectory --robot " + quoted(dir / "spinner.urdf") +
                             " --trajectory " + quoted(write_trajectory(dir, "0.5")));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_EQ(run.err.find("'q' limit"), std::string::npos) << run.err;
  const std::vector<std::string> spin = row_of(run.out, "1");
  ASSERT_EQ(spin.size(), 11u) << run.out;
  EXPECT_EQ(spin[3], "(none)");
  EXPECT_EQ(run.out.find('!'), std::string::npos) << run.out;
}

TEST(ModelidContinuousJoint, CheckTrajectoryStillChecksTheVelocityLimit) {
  const fs::path dir = test_folder();
  write_text(dir / "spinner.urdf", kUrdf);
  // |dq| = pi = 3.14 of 2: 157%.
  const CliRun run = modelid("check-trajectory --robot " + quoted(dir / "spinner.urdf") +
                             " --trajectory " + quoted(write_trajectory(dir, "1")));
  EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
  const std::vector<std::string> spin = row_of(run.out, "1");
  ASSERT_EQ(spin.size(), 11u) << run.out;
  EXPECT_EQ(spin[7], "157.1%!");
  EXPECT_NE(run.err.find("1 limit is exceeded"), std::string::npos) << run.err;
}

TEST(ModelidContinuousJoint, DesignNeedsNoPositionLimit) {
  const fs::path dir = test_folder();
  write_text(dir / "spinner.urdf", kUrdf);
  const CliRun run = modelid("design --robot " + quoted(dir / "spinner.urdf") +
                             " --period 2 --harmonics 2 --margin 0.9 --samples 60 --starts 2 "
                             "--seed 5 --ddq-limit 10 -o " +
                             quoted(dir / "design.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  // The design keeps every limit that applies: the check passes with the same limits.
  const CliRun check = modelid("check-trajectory --robot " + quoted(dir / "spinner.urdf") +
                               " --ddq-limit 10 --trajectory " + quoted(dir / "design.yaml"));
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  EXPECT_EQ(check.out.find('!'), std::string::npos) << check.out;
}

// Joint 1 swings over [9.5, 10.5] rad (write_trajectory): against [9, 11] its q use is the
// distance from the middle, 0.5, over half the range, 1: 50.0%; against [-3, 3], 10.5 / 3.
TEST(ModelidContinuousJoint, QLimitGivesAContinuousJointARange) {
  const fs::path dir = test_folder();
  write_text(dir / "spinner.urdf", kUrdf);
  const std::string check = "check-trajectory --robot " + quoted(dir / "spinner.urdf") +
                            " --trajectory " + quoted(write_trajectory(dir, "0.5"));
  const CliRun within = modelid(check + " --q-limit spin=9,11");
  ASSERT_EQ(within.exit_code, 0) << within.out << within.err;
  const std::vector<std::string> spin = row_of(within.out, "1");
  ASSERT_GE(spin.size(), 5u) << within.out;
  EXPECT_NE(within.out.find("50.0%"), std::string::npos) << within.out;
  // By number, and beyond the range: 350.0% and exit 1.
  const CliRun beyond = modelid(check + " --q-limit 1=-3,3");
  EXPECT_EQ(beyond.exit_code, 1) << beyond.out << beyond.err;
  EXPECT_NE(beyond.out.find("350.0%!"), std::string::npos) << beyond.out;
  // simulate refuses the trajectory against the range given.
  const CliRun simulate =
      modelid("simulate --robot " + quoted(dir / "spinner.urdf") + " --trajectory " +
              quoted(dir / "spin.yaml") + " --q-limit spin=-3,3 -o " + quoted(dir / "run.csv"));
  EXPECT_EQ(simulate.exit_code, 1) << simulate.out << simulate.err;
  EXPECT_NE(simulate.err.find("leaves its q limit"), std::string::npos) << simulate.err;
  EXPECT_FALSE(fs::exists(dir / "run.csv"));
}

TEST(ModelidContinuousJoint, DesignKeepsAQLimitGiven) {
  const fs::path dir = test_folder();
  write_text(dir / "spinner.urdf", kUrdf);
  const std::string robot = " --robot " + quoted(dir / "spinner.urdf");
  const CliRun run = modelid("design" + robot +
                             " --period 2 --harmonics 2 --margin 0.9 --samples 60 --starts 2 "
                             "--seed 5 --ddq-limit 10 --q-limit spin=-0.2,0.2 -o " +
                             quoted(dir / "design.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  // The written header says how to make it again, the range included.
  EXPECT_NE(read_text(dir / "design.yaml").find("--q-limit spin=-0.2,0.2"), std::string::npos);
  const CliRun check = modelid("check-trajectory" + robot + " --ddq-limit 10 --trajectory " +
                               quoted(dir / "design.yaml") + " --q-limit spin=-0.2,0.2");
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  EXPECT_EQ(check.out.find('!'), std::string::npos) << check.out;
}

TEST(ModelidContinuousJoint, QLimitUsageErrorsNameTheOption) {
  const fs::path dir = test_folder();
  write_text(dir / "spinner.urdf", kUrdf);
  const std::string check = "check-trajectory --robot " + quoted(dir / "spinner.urdf") +
                            " --trajectory " + quoted(write_trajectory(dir, "0.5"));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"spin", "--q-limit 'spin': expected JOINT=LO,HI"},
      {"spn=1,2", "no moving joint 'spn' (did you mean 'spin'?)"},
      {"3=1,2", "or its number, 1 to 2"},
      {"spin=2,1", "the lower bound must be below the upper one"},
      {"spin=1", "expected two bounds LO,HI"},
      {"spin=a,1", "--q-limit"},
  };
  for (const auto& [value, message] : cases) {
    const CliRun run = modelid(check + " --q-limit " + value);
    EXPECT_EQ(run.exit_code, 2) << value << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << value << "\n" << run.err;
  }
  const CliRun twice = modelid(check + " --q-limit spin=1,2 --q-limit 1=0,3");
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_NE(twice.err.find("joint 1 is given a range twice"), std::string::npos) << twice.err;
}

}  // namespace
}  // namespace modelgen::test
