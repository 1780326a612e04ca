// `modelgen --angle-tolerance` as a user meets it: a URDF with rounded quarter turns generates
// the same code as the one written with exact angles (no constants of 1e-6 and below, the
// same operation counts), each snapped value is named on standard error, `describe` lists them,
// and `--angle-tolerance 0` takes the file as written, as modelgen did before.

#include <algorithm>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRounded = "tests/model/rounded_angles/rounded_arm.urdf";
constexpr const char* kExact = "tests/model/rounded_angles/exact_arm.urdf";

// Numeric literals of magnitude below 1e-5 written in exponent form, as the emitter writes them.
int tiny_constants(const std::string& code) {
  static const std::regex tiny(R"([0-9.]+e-(0[6-9]|[1-9][0-9]))");
  return static_cast<int>(std::distance(std::sregex_iterator(code.begin(), code.end(), tiny),
                                        std::sregex_iterator()));
}

// The generated source from its first #include on (the banner names the input and its
// SHA-256), with the file stems and the robot's name (rounded_arm in both files) replaced.
std::string code_body(const fs::path& file) {
  const std::string text = test::read_text(file);
  const std::size_t code = text.find("#include");
  if (code == std::string::npos) return "no #include in " + file.string();
  return std::regex_replace(text.substr(code), std::regex("(rounded|exact)_arm"), "STEM");
}

// Every generated source of `stem` in `dir` (the tables and a file per function), in name
// order, each from its first #include on.
std::string generated_code(const fs::path& dir, const std::string& stem) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name == stem + ".cpp" || (name.rfind(stem + "_", 0) == 0 && entry.path().extension() == ".cpp")) {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  std::string code;
  for (const fs::path& file : files) code += code_body(file);
  return code;
}

TEST(AngleToleranceCli, RoundedUrdfGeneratesTheCodeOfTheExactOne) {
  const fs::path dir = test::test_folder("angles");
  const test::CliRun exact = test::modelgen(test::quoted_source(kExact) + " -o " + test::quoted(dir));
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  EXPECT_EQ(exact.err, "");
  const test::CliRun rounded =
      test::modelgen(test::quoted_source(kRounded) + " -o " + test::quoted(dir));
  ASSERT_EQ(rounded.exit_code, 0) << rounded.err;
  // Compared as a whole (a diff of the two would be pages long).
  const std::string rounded_code = generated_code(dir, "rounded_arm");
  EXPECT_GT(rounded_code.size(), 100000u) << "the function files are missing";
  EXPECT_TRUE(rounded_code == generated_code(dir, "exact_arm"))
      << "the code generated from the rounded angles differs from the exact one's";
  EXPECT_EQ(tiny_constants(rounded_code), 0);
  // 17 values written rounded (angle_snapping_test lists them), one note each.
  std::size_t notes = 0;
  for (std::size_t at = rounded.err.find(": note: "); at != std::string::npos;
       at = rounded.err.find(": note: ", at + 1)) {
    ++notes;
  }
  EXPECT_EQ(notes, 17u) << rounded.err;
  EXPECT_NE(rounded.err.find("rounded_arm.urdf:66: note: joint 'upper_arm': origin rpy roll "
                             "1.57075 taken as pi/2 (4.6e-05 rad off"),
            std::string::npos)
      << rounded.err;
}

TEST(AngleToleranceCli, ZeroToleranceTakesTheFileAsWritten) {
  const fs::path dir = test::test_folder("angles_zero");
  const test::CliRun run = test::modelgen(test::quoted_source(kRounded) + " -o " +
                                          test::quoted(dir) + " --angle-tolerance 0");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  // The tilts of 3e-6..5e-5 rad are in the code as sines and cosines of them.
  EXPECT_GT(tiny_constants(generated_code(dir, "rounded_arm")), 100);
  EXPECT_NE(test::read_text(dir / "rounded_arm.cpp").find("--angle-tolerance 0"),
            std::string::npos)
      << "the banner's command line must say how the file was read";
}

TEST(AngleToleranceCli, DescribeAndBaseNameTheSnappedAngles) {
  const test::CliRun describe = test::modelgen("describe " + test::quoted_source(kRounded));
  ASSERT_EQ(describe.exit_code, 0) << describe.err;
  EXPECT_NE(describe.out.find("angles taken as exact quarter turns"), std::string::npos);
  EXPECT_NE(describe.out.find("  line 66: joint 'upper_arm': origin rpy roll 1.57075 taken as pi/2"),
            std::string::npos)
      << describe.out;
  const test::CliRun base = test::modelgen("base " + test::quoted_source(kRounded));
  ASSERT_EQ(base.exit_code, 0) << base.err;
  const test::CliRun exact_base = test::modelgen("base " + test::quoted_source(kExact));
  EXPECT_EQ(std::regex_replace(base.out, std::regex("rounded_arm"), "arm"),
            std::regex_replace(exact_base.out, std::regex("rounded_arm"), "arm"));
  EXPECT_NE(base.err.find(": note: "), std::string::npos);
}

TEST(AngleToleranceCli, ToleranceMustBeAnAngleBelowAnEighthTurn) {
  for (const char* bad : {"-1e-4", "1", "abc"}) {
    const test::CliRun run = test::modelgen("describe " + test::quoted_source(kRounded) +
                                            " --angle-tolerance " + bad);
    EXPECT_EQ(run.exit_code, 2) << bad;
    EXPECT_NE(run.err.find("--angle-tolerance"), std::string::npos) << run.err;
  }
}

// modelid reads a description file the same way (its numeric reference then matches the code
// modelgen generates), and takes the same option.
TEST(AngleToleranceCli, ModelidReadsDescriptionsAsModelgenDoes) {
  const test::CliRun exact = test::modelid("check " + test::quoted_source(kExact));
  ASSERT_EQ(exact.exit_code, 0) << exact.err;
  const test::CliRun rounded = test::modelid("check " + test::quoted_source(kRounded));
  ASSERT_EQ(rounded.exit_code, 0) << rounded.err;
  EXPECT_EQ(rounded.out, exact.out);
  EXPECT_NE(rounded.err.find(": note: joint 'upper_arm': origin rpy roll 1.57075 taken as pi/2"),
            std::string::npos)
      << rounded.err;
  const test::CliRun as_written =
      test::modelid("check " + test::quoted_source(kRounded) + " --angle-tolerance 0");
  ASSERT_EQ(as_written.exit_code, 0) << as_written.err;
  EXPECT_NE(as_written.out, exact.out);
  EXPECT_EQ(as_written.err, "");
}

// The COMAU Smart Six URDF of ../shared (not shipped: no license) writes 1.57075 and 3.14159.
TEST(AngleToleranceCli, ComauSmartSixBaseParameters) {
  const std::string path = test::shared_path("robots-ref/comau_smart_six.urdf");
  if (!fs::exists(path)) GTEST_SKIP() << "no " << path << " (../shared is not there)";
  const test::CliRun run = test::modelgen("base " + test::quoted(path));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("58 of 84 standard"), std::string::npos) << run.out;
  const test::CliRun as_written = test::modelgen("base " + test::quoted(path) + " --angle-tolerance 0");
  EXPECT_NE(as_written.out.find("60 of 84 standard"), std::string::npos) << as_written.out;
}

}  // namespace
}  // namespace modelgen
