// The description limits (description_limits.hpp) on inputs too large to keep as files under
// tests/bad_inputs/: each is refused with a positioned InputError naming the limit, quickly,
// instead of an impossible allocation (a 2000-link chain asked stacked_regressor for 21 GB), a
// crash (a chain of 9999 fixed links overflowed the call stack) or a long run.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "modelgen/model/description_limits.hpp"
#include "modelgen/model/load_robot.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;

// A URDF chain: `moving` continuous joints after `fixed` fixed ones, one link per joint.
std::string urdf_chain(int fixed, int moving) {
  std::string text = "<robot name=\"chain\">\n  <link name=\"l0\"/>\n";
  for (int i = 1; i <= fixed + moving; ++i) {
    const std::string type = i <= fixed ? "fixed" : "continuous";
    text += "  <link name=\"l" + std::to_string(i) + "\"/>\n  <joint name=\"j" +
            std::to_string(i) + "\" type=\"" + type + "\"><parent link=\"l" +
            std::to_string(i - 1) + "\"/><child link=\"l" + std::to_string(i) +
            "\"/><origin xyz=\"0.1 0 0\" rpy=\"1.5707963267948966 0 0\"/></joint>\n";
  }
  return text + "</robot>\n";
}

fs::path write(const std::string& name, const std::string& text) {
  const fs::path path = test::test_folder("limits") / name;
  test::write_text(path, text);
  return path;
}

// The InputError of loading `path`, or "" when it loads.
std::string load_error(const fs::path& path) {
  try {
    load_robot(path.string());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DescriptionLimits, TwoThousandLinkChainIsRefusedAtJoint33) {
  const fs::path path = write("chain2000.urdf", urdf_chain(0, 2000));
  const auto start = std::chrono::steady_clock::now();
  const std::string error = load_error(path);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Joint 33 is written on line 2 + 2 * 33 (two lines per link and joint after the header).
  EXPECT_NE(error.find("chain2000.urdf:68: error: joint 'j33' is moving joint 33; modelgen "
                       "models at most 32 moving joints"),
            std::string::npos)
      << error;
  EXPECT_LT(seconds, 5.0);
}

TEST(DescriptionLimits, ThirtyTwoMovingJointsLoad) {
  EXPECT_EQ(load_error(write("chain32.urdf", urdf_chain(0, kMaxMovingJoints))), "");
}

TEST(DescriptionLimits, LongChainsOfFixedLinksLoadWithoutRecursion) {
  // 9 998 fixed joints, then one moving joint: 10 000 links, the most a URDF may have.
  const fs::path path = write("fixed.urdf", urdf_chain(kMaxUrdfLinks - 2, 1));
  const RobotModel model = load_robot(path.string());
  EXPECT_EQ(model.dof(), 1);
  // The moving joint sits 9 999 x 0.1 m out along x (every origin turns about x only).
  EXPECT_NEAR(model.tree.bodies[0].fixed.translation[0], 999.9, 1e-6);
}

TEST(DescriptionLimits, MoreThanTenThousandLinksAreRefused) {
  const std::string error = load_error(write("links.urdf", urdf_chain(kMaxUrdfLinks - 1, 1)));
  // Link l<i> is written on line 2 i + 1: the 10 001st, l10000, on line 20 001.
  EXPECT_NE(error.find(":20001: error: more than 10000 links; a URDF may hold at most that many"),
            std::string::npos)
      << error;
}

TEST(DescriptionLimits, FilesBeyond32MiBAreRefusedBeforeReading) {
  std::string text = "name: arm\njoints:\n  - {type: revolute, alpha: 0, d: 0, theta: 0, r: 0}\n";
  text += "# " + std::string(kMaxDescriptionBytes, 'x') + "\n";
  const fs::path path = write("large.yaml", text);
  EXPECT_EQ(load_error(path), path.string() + ": error: the file has " +
                                  std::to_string(text.size()) +
                                  " bytes, beyond the limit of 33554432 bytes for a robot "
                                  "description (README, Limits)");
}

TEST(DescriptionLimits, CommandLineExitsWithOneNotAnInternalError) {
  const fs::path path = write("chain2000.urdf", urdf_chain(0, 2000));
  for (const char* command : {"base ", "describe ", ""}) {
    const std::string output = std::string(command).empty()
                                   ? " -o " + test::quoted(test::test_folder("limits_out"))
                                   : "";
    const test::CliRun run = test::modelgen(command + test::quoted(path) + output);
    EXPECT_EQ(run.exit_code, 1) << command << run.err;
    EXPECT_NE(run.err.find("at most 32 moving joints"), std::string::npos) << run.err;
  }
}

}  // namespace
}  // namespace modelgen
