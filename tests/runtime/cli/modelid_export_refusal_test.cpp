// What modelid export refuses to write, and that a refusal writes nothing: links far from their
// a-priori values or outside their geometry's region (unless --force), estimates without
// --physical or of another robot, an unwritable output, a compiled-in model's name. What it
// writes: modelid_export_test.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tinyxml2.h>
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "modelgen/model/load_robot.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/export_support.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::consistent_standard;
using test::estimate_of;
using test::kToolArm;
using test::modelid;
using test::quoted;
using test::tool_arm_estimate;

TEST(ModelidExport, ALinkFarFromItsAPrioriValuesIsRefusedUnlessForced) {
  const fs::path dir = test::test_folder("export_far");
  test::write_text(dir / "arm.urdf", kToolArm);
  // Link 2's body (l2 and the tool, 2.3 kg a-priori) at 0.4 times its a-priori mass, its centre
  // of mass unchanged: off by more than a factor 2.
  test::write_text(dir / "est.json", tool_arm_estimate(dir / "arm.urdf", 0.4).dump(2));
  const std::string command = "export --robot " + quoted(dir / "arm.urdf") + " --params " +
                              quoted(dir / "est.json") + " -o " + quoted(dir / "id.urdf");
  const CliRun refused = modelid(command);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find("link 'l2': mass 0.4 x its a-priori value"), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("--force"), std::string::npos) << refused.err;
  EXPECT_EQ(refused.err.find("link 'l1'"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir / "id.urdf"));
  const CliRun forced = modelid(command + " --force");
  ASSERT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_TRUE(fs::exists(dir / "id.urdf"));
}

TEST(ModelidExport, AFitThatStoppedShortIsRefusedUnlessForced) {
  // The tool arm at its a-priori values (no link far), from a consistent fit whose optimiser
  // stopped short ("converged": false, as fit --physical writes it then): refused, nothing
  // written; with --force written; the same estimate marked converged is written.
  const fs::path dir = test::test_folder("export_stopped");
  test::write_text(dir / "arm.urdf", kToolArm);
  nlohmann::json est = tool_arm_estimate(dir / "arm.urdf", 1.0);
  est["physical"]["converged"] = false;
  test::write_text(dir / "est.json", est.dump(2));
  const std::string command = "export --robot " + quoted(dir / "arm.urdf") + " --params " +
                              quoted(dir / "est.json") + " -o " + quoted(dir / "id.urdf");
  const CliRun refused = modelid(command);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find("stopped short of its optimum"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir / "id.urdf"));
  const CliRun forced = modelid(command + " --force");
  ASSERT_EQ(forced.exit_code, 0) << forced.err;
  EXPECT_TRUE(fs::exists(dir / "id.urdf"));
  fs::remove(dir / "id.urdf");
  est["physical"]["converged"] = true;
  test::write_text(dir / "est.json", est.dump(2));
  const CliRun accepted = modelid(command);
  ASSERT_EQ(accepted.exit_code, 0) << accepted.err;
  EXPECT_TRUE(fs::exists(dir / "id.urdf"));
}

// One link: a 0.1 x 0.1 x 0.4 box from the joint up, its a-priori mass 1 kg at its centre.
constexpr const char* kBoxArm = R"(<?xml version="1.0"?>
<robot name="box_arm">
  <link name="base"/>
  <link name="a">
    <inertial><origin xyz="0 0 0.2"/><mass value="1"/>
      <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
    <collision><origin xyz="0 0 0.2"/><geometry><box size="0.1 0.1 0.4"/></geometry></collision>
  </link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="a"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
</robot>
)";

TEST(ModelidExport, ALinkOutsideItsGeometryIsRefusedUnlessForced) {
  // The link's mass 9 cm off the box's axis (not far from its a-priori centre, 10 cm): beyond
  // the ellipsoid around the box, whose semi-axis there is sqrt(3) x 5 cm = 8.7 cm.
  const fs::path dir = test::test_folder("export_region");
  test::write_text(dir / "arm.urdf", kBoxArm);
  const RobotModel robot = load_robot((dir / "arm.urdf").string());
  Eigen::VectorXd standard = consistent_standard(robot);
  const double values[] = {
      1e-4, 0, -0.09 * 0.2, 1e-4 + 0.09 * 0.09 + 0.04, 0, 1e-4 + 0.09 * 0.09, 0.09, 0, 0.2, 1};
  const char* stems[] = {"XX", "XY", "XZ", "YY", "YZ", "ZZ", "MX", "MY", "MZ", "M"};
  for (int s = 0; s < 10; ++s) standard[robot.param_index(std::string(stems[s]) + "1")] = values[s];
  standard[robot.param_index("XX1")] += 0.04;  // the parallel-axis terms about the origin
  test::write_text(dir / "est.json", estimate_of((dir / "arm.urdf").string(), standard).dump(2));
  const std::string command = "export --robot " + quoted(dir / "arm.urdf") + " --params " +
                              quoted(dir / "est.json") + " -o " + quoted(dir / "id.urdf");
  const CliRun refused = modelid(command);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find("link 'a': its mass reaches outside the region its geometry gives"),
            std::string::npos)
      << refused.err;
  EXPECT_EQ(refused.err.find("x its a-priori value"), std::string::npos) << refused.err;
  EXPECT_EQ(refused.err.find("from its a-priori position"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir / "id.urdf"));
  const CliRun forced = modelid(command + " --force");
  ASSERT_EQ(forced.exit_code, 0) << forced.err;
}

TEST(ModelidExport, AFitWithoutPhysicalIsRefused) {
  const fs::path dir = test::test_folder("export");
  const std::string path = test::source_path("robots/tx40.yaml");
  nlohmann::json est = estimate_of(path, consistent_standard(load_robot(path)));
  est.erase("standard");
  est.erase("physical");
  test::write_text(dir / "est.json", est.dump(2));
  const CliRun run = modelid("export --robot " + quoted(fs::path(path)) + " --params " +
                             quoted(dir / "est.json") + " -o " + quoted(dir / "id.yaml"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("refit with 'modelid fit --physical"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "id.yaml"));
}

TEST(ModelidExport, AnEstimateOfAnotherRobotIsRefused) {
  const fs::path dir = test::test_folder("export");
  const std::string kr150 = test::source_path("robots/kr150.yaml");
  test::write_text(dir / "est.json",
                   estimate_of(kr150, consistent_standard(load_robot(kr150))).dump(2));
  const CliRun run =
      modelid("export --robot " + test::quoted_source("robots/tx40.yaml") + " --params " +
              quoted(dir / "est.json") + " -o " + quoted(dir / "id.yaml"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("the estimate belongs to another model"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "id.yaml"));
}

TEST(ModelidExport, AnUnwritableOutputChangesNothing) {
  const fs::path dir = test::test_folder("export");
  test::write_text(dir / "arm.urdf", kToolArm);
  test::write_text(dir / "est.json", tool_arm_estimate(dir / "arm.urdf", 1.25).dump(2));
  const fs::path out = dir / "missing" / "id.urdf";
  const CliRun run = modelid("export --robot " + quoted(dir / "arm.urdf") + " --params " +
                             quoted(dir / "est.json") + " -o " + quoted(out));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.err, out.string() +
                         ": error: cannot write the file: No such file or directory (no file "
                         "was changed)\n");
  EXPECT_FALSE(fs::exists(dir / "missing"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

TEST(ModelidExport, ACompiledInModelNameIsNotADescription) {
  const fs::path dir = test::test_folder("export");
  const CliRun run = modelid("export --robot tx40 --params " + quoted(dir / "est.json") + " -o " +
                             quoted(dir / "id.yaml"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("export needs the description file"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace modelgen
