// The modelgen executable as a user runs it: generation writes the three files, a bad
// description leaves an existing output directory exactly as it was, usage errors exit 2.

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

CliRun modelgen(const std::string& arguments) {
  // Per-test output files: CTest runs the tests of this file in parallel processes.
  const std::string test = testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path dir = fs::path(testing::TempDir());
  const fs::path out = dir / ("cli_out_" + test), err = dir / ("cli_err_" + test);
  const std::string command = "'" + std::string(MODELGEN_BINARY_DIR) + "/bin/modelgen' " +
                              arguments + " >'" + out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  CliRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = read(out);
  run.err = read(err);
  return run;
}

fs::path fresh_directory(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / name;
  fs::remove_all(dir);
  return dir;
}

TEST(ModelgenCli, GeneratesHeaderSourceAndManifest) {
  const fs::path dir = fresh_directory("cli_generate");
  const CliRun run = modelgen("'" + test::source_path("robots/tx40.yaml") + "' -o '" + dir.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "");
  for (const char* name : {"tx40.hpp", "tx40.cpp", "tx40.json"}) {
    EXPECT_TRUE(fs::exists(dir / name)) << name;
  }
  EXPECT_NE(read(dir / "tx40.hpp").find("namespace tx40 {"), std::string::npos);
}

TEST(ModelgenCli, BadDescriptionLeavesExistingOutputUntouched) {
  const fs::path dir = fresh_directory("cli_keep");
  fs::create_directories(dir);
  std::ofstream(dir / "unknown_key.hpp") << "previous content\n";
  const CliRun run = modelgen("'" + test::source_path("tests/bad_inputs/yaml/unknown_key.yaml") +
                           "' -o '" + dir.string() + "'");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("unknown_key.yaml:4:22: error: unknown key 'alpah'"), std::string::npos)
      << run.err;
  EXPECT_EQ(read(dir / "unknown_key.hpp"), "previous content\n");
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "unknown_key.hpp");
  }
  EXPECT_EQ(files, 1u);
}

TEST(ModelgenCli, FloatOnlyGeneration) {
  const fs::path dir = fresh_directory("cli_float");
  const CliRun run = modelgen("'" + test::source_path("robots/tx40.yaml") + "' -o '" + dir.string() +
                           "' --scalar float");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string header = read(dir / "tx40.hpp");
  EXPECT_EQ(header.find("double"), std::string::npos);
  EXPECT_NE(header.find("const float* q"), std::string::npos);
  EXPECT_NE(header.find("// Regenerate: modelgen tx40.yaml -o <dir> --scalar float"), std::string::npos);
}

TEST(ModelgenCli, BasePrintsRegroupingRelations) {
  const CliRun run = modelgen("base '" + test::source_path("robots/tx40.yaml") + "'");
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
  const std::string robot = "'" + test::source_path("robots/tx40.yaml") + "'";
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
