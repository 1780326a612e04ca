// The modelgen executable as a user runs it: generation writes the three files, a bad
// description leaves an existing output directory exactly as it was, usage errors exit 2.

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::modelgen;
using test::read_text;

fs::path fresh_directory(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / name;
  fs::remove_all(dir);
  return dir;
}

TEST(ModelgenCli, GeneratesHeaderSourceAndManifest) {
  const fs::path dir = fresh_directory("cli_generate");
  const CliRun run = modelgen(test::quoted_source("robots/tx40.yaml") + " -o " + test::quoted(dir));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "");
  for (const char* name : {"tx40.hpp", "tx40.cpp", "tx40.json"}) {
    EXPECT_TRUE(fs::exists(dir / name)) << name;
  }
  EXPECT_NE(read_text(dir / "tx40.hpp").find("namespace tx40 {"), std::string::npos);
}

TEST(ModelgenCli, BadDescriptionLeavesExistingOutputUntouched) {
  const fs::path dir = fresh_directory("cli_keep");
  fs::create_directories(dir);
  std::ofstream(dir / "unknown_key.hpp") << "previous content\n";
  const CliRun run = modelgen(test::quoted_source("tests/bad_inputs/yaml/unknown_key.yaml") +
                              " -o " + test::quoted(dir));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("unknown_key.yaml:4:22: error: unknown key 'alpah'"), std::string::npos)
      << run.err;
  EXPECT_EQ(read_text(dir / "unknown_key.hpp"), "previous content\n");
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "unknown_key.hpp");
  }
  EXPECT_EQ(files, 1u);
}

TEST(ModelgenCli, FloatOnlyGeneration) {
  const fs::path dir = fresh_directory("cli_float");
  const CliRun run = modelgen(test::quoted_source("robots/tx40.yaml") + " -o " + test::quoted(dir) +
                              " --scalar float");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string header = read_text(dir / "tx40.hpp");
  EXPECT_EQ(header.find("double"), std::string::npos);
  EXPECT_NE(header.find("const float* q"), std::string::npos);
  EXPECT_NE(header.find("// Regenerate: modelgen tx40.yaml -o <dir> --scalar float"), std::string::npos);
}

TEST(ModelgenCli, BasePrintsRegroupingRelations) {
  const CliRun run = modelgen("base " + test::quoted_source("robots/tx40.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Khalil's rule for the TX-40 (Table I): ZZ1R absorbs Ia1, YY2, YY3, 2 r3 MZ3 = 0.07 MZ3 and
  // (d3^2 + r3^2) = 0.05185 times the masses beyond link 2.
  EXPECT_NE(run.out.find("ZZ1R = ZZ1 + Ia1 + YY2 + YY3 + 0.07 MZ3 + 0.05185 M3"), std::string::npos)
      << run.out;
  // 6 x 14 joint parameters, motor 6's Iam6 Fvm6 Fcm6 (eq. 26), 10 of the payload frame.
  EXPECT_NE(run.out.find("61 of 97"), std::string::npos) << run.out;
  // The same relation with the symbols of Table I (closed-form rules).
  EXPECT_NE(run.out.find("= ZZ1 + Ia1 + YY2 + YY3 + 2*r3 MZ3 + (d3^2 + r3^2) M3"), std::string::npos)
      << run.out;
}

TEST(ModelgenCli, UsageErrorsExitTwo) {
  const std::string robot = test::quoted_source("robots/tx40.yaml");
  for (const std::string& arguments :
       {robot, robot + " -o", robot + " -o x --scalar half", robot + " --bogus", std::string(),
        std::string("describe")}) {
    const CliRun run = modelgen(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments;
    EXPECT_NE(run.err.find("usage: modelgen"), std::string::npos) << arguments;
  }
}

}  // namespace
}  // namespace modelgen
