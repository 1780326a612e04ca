// The modelgen executable as a user runs it: generation writes the header, the tables, a file
// per function and the manifest; --functions keeps the chosen entry points and their callees; a
// bad description leaves an existing output directory exactly as it was, usage errors exit 2.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

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
  for (const char* name : {"tx40.hpp", "tx40.cpp", "tx40.json", "tx40_inverse_dynamics.cpp",
                           "tx40_idim_regressor_sincos.cpp", "tx40_drive_torque_jacobian.cpp"}) {
    EXPECT_TRUE(fs::exists(dir / name)) << name;
  }
  EXPECT_NE(read_text(dir / "tx40.hpp").find("namespace tx40 {"), std::string::npos);
  // Each function file defines its entry point, and only it.
  const std::string inverse_dynamics = read_text(dir / "tx40_inverse_dynamics.cpp");
  EXPECT_NE(inverse_dynamics.find("void inverse_dynamics(const double* q"), std::string::npos);
  EXPECT_NE(inverse_dynamics.find("void inverse_dynamics(const float* q"), std::string::npos);
  EXPECT_EQ(inverse_dynamics.find("void idim_regressor("), std::string::npos);
  EXPECT_EQ(inverse_dynamics.find("void inverse_dynamics_sincos("), std::string::npos);
  EXPECT_EQ(read_text(dir / "tx40.cpp").find("void "), std::string::npos);
}

// The files of a directory, sorted.
std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(ModelgenCli, FunctionsKeepsTheChosenEntryPointsAndTheirCallees) {
  const fs::path dir = fresh_directory("cli_functions");
  const CliRun run = modelgen(test::quoted_source("robots/tx40.yaml") + " -o " +
                              test::quoted(dir) +
                              " --functions drive_torque_jacobian,inverse_dynamics_sincos");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("note: --functions: drive_torque_jacobian calls idim_regressor_standard, "
                         "which is generated too"),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("note: --functions: inverse_dynamics_sincos takes sin_q, cos_q from "
                         "joint_sincos, which is generated too"),
            std::string::npos)
      << run.err;
  EXPECT_EQ(files_in(dir), (std::vector<std::string>{
                               "tx40.cpp", "tx40.hpp", "tx40.json",
                               "tx40_drive_torque_jacobian.cpp",
                               "tx40_idim_regressor_standard.cpp",
                               "tx40_inverse_dynamics_sincos.cpp", "tx40_joint_sincos.cpp"}));
  const std::string header = read_text(dir / "tx40.hpp");
  EXPECT_NE(header.find("void inverse_dynamics_sincos("), std::string::npos);
  EXPECT_EQ(header.find("void inverse_dynamics("), std::string::npos);
  EXPECT_EQ(header.find("void mass_matrix("), std::string::npos);
  // Without all of its members the runtime's Model struct is left out.
  EXPECT_EQ(header.find("struct Model {"), std::string::npos);
  // The banner's command names the selection in file order, whatever order it was given in.
  EXPECT_NE(header.find("// Regenerate: modelgen tx40.yaml -o <dir> --functions "
                        "inverse_dynamics_sincos,drive_torque_jacobian"),
            std::string::npos);
  const std::string manifest = read_text(dir / "tx40.json");
  EXPECT_NE(manifest.find("\"tx40_idim_regressor_standard.cpp\""), std::string::npos);
  EXPECT_EQ(manifest.find("\"name\": \"mass_matrix\""), std::string::npos);
}

// Only the builders of the chosen functions run (and the derivation of the packed drive
// regressor's layout, for the header), and operand order depends on structure alone,
// so a function's code is the same generated alone as with all the others.
TEST(ModelgenCli, AFunctionGeneratedAloneHasTheCodeOfTheFullRun) {
  const fs::path all = fresh_directory("cli_alone_all"), alone = fresh_directory("cli_alone");
  const std::string robot = test::quoted_source("robots/kr150.yaml");
  ASSERT_EQ(modelgen(robot + " -o " + test::quoted(all)).exit_code, 0);
  ASSERT_EQ(modelgen(robot + " -o " + test::quoted(alone) + " --functions mass_matrix").exit_code,
            0);
  const auto code = [](const fs::path& file) {
    const std::string text = read_text(file);
    return text.substr(text.find("#include"));
  };
  EXPECT_TRUE(code(all / "kr150_mass_matrix.cpp") == code(alone / "kr150_mass_matrix.cpp"));
  EXPECT_GT(code(alone / "kr150_mass_matrix.cpp").size(), 10000u);
}

TEST(ModelgenCli, AFullRunAfterASelectionAndBackRemovesNothingElse) {
  const fs::path dir = fresh_directory("cli_functions_again");
  const std::string base = test::quoted_source("robots/tx40.yaml") + " -o " + test::quoted(dir);
  ASSERT_EQ(modelgen(base).exit_code, 0);
  const std::size_t all = files_in(dir).size();
  // One header, one table source, one manifest and a file per entry point.
  EXPECT_EQ(all, 3u + 24u);
  std::ofstream(dir / "controller.cpp") << "// the user's own file\n";
  const CliRun narrowed = modelgen(base + " --functions inverse_dynamics");
  ASSERT_EQ(narrowed.exit_code, 0) << narrowed.err;
  // The function files of the first run are gone; the user's file stays.
  EXPECT_EQ(files_in(dir), (std::vector<std::string>{"controller.cpp", "tx40.cpp", "tx40.hpp",
                                                     "tx40.json", "tx40_inverse_dynamics.cpp"}));
  ASSERT_EQ(modelgen(base).exit_code, 0);
  EXPECT_EQ(files_in(dir).size(), all + 1);
}

// A description whose stem is another's stem plus a function name (tx40_drive_torque.yaml
// beside tx40.yaml) makes a file name the other makes too: neither run replaces or removes
// the other's file.
TEST(ModelgenCli, FilesOfAnotherDescriptionInTheFolderAreNeitherReplacedNorRemoved) {
  const fs::path dir = fresh_directory("cli_two_stems");
  const fs::path inputs = fresh_directory("cli_two_stems_inputs");
  fs::create_directories(inputs);
  fs::copy_file(test::source_path("robots/tx40.yaml"), inputs / "tx40_drive_torque.yaml");
  ASSERT_EQ(modelgen(test::quoted(inputs / "tx40_drive_torque.yaml") + " -o " + test::quoted(dir))
                .exit_code,
            0);
  const std::string tables = read_text(dir / "tx40_drive_torque.cpp");
  ASSERT_NE(tables.find("kStandardParamNames"), std::string::npos);
  const std::string tx40 = test::quoted_source("robots/tx40.yaml") + " -o " + test::quoted(dir);
  const CliRun full = modelgen(tx40);
  EXPECT_EQ(full.exit_code, 1);
  EXPECT_NE(full.err.find("tx40_drive_torque.cpp: error: was generated from another description "
                          "(its first line: '// tx40_drive_torque.cpp: generated by modelgen"),
            std::string::npos)
      << full.err;
  EXPECT_FALSE(fs::exists(dir / "tx40.hpp")) << "nothing is written when one file is refused";
  // A selection without that function writes its files and leaves the other's alone.
  const CliRun narrowed = modelgen(tx40 + " --functions inverse_dynamics");
  EXPECT_EQ(narrowed.exit_code, 0) << narrowed.err;
  EXPECT_EQ(read_text(dir / "tx40_drive_torque.cpp"), tables);
}

TEST(ModelgenCli, UnknownFunctionIsAUsageErrorListingTheValidOnes) {
  const std::string base =
      test::quoted_source("robots/tx40.yaml") + " -o " + test::quoted(fresh_directory("cli_bad_f"));
  const CliRun typo = modelgen(base + " --functions inverse_dynamics,idim_regresor");
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.err.find("--functions: unknown function 'idim_regresor' (did you mean "
                          "'idim_regressor'?); the functions are: idim_regressor_standard, "),
            std::string::npos)
      << typo.err;
  const CliRun identified = modelgen(base + " --functions inverse_dynamics_identified");
  EXPECT_EQ(identified.exit_code, 2);
  EXPECT_NE(identified.err.find("inverse_dynamics_identified uses identified constants; it needs "
                                "--params"),
            std::string::npos)
      << identified.err;
  const CliRun empty = modelgen(base + " --functions inverse_dynamics,,mass_matrix");
  EXPECT_EQ(empty.exit_code, 2);
  EXPECT_NE(empty.err.find("--functions: empty item"), std::string::npos) << empty.err;
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
