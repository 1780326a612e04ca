// modelgen --loadable as a user runs it: STEM_loadable.cpp besides the usual files, listed in the
// manifest with the sources a shared library compiles; every other file as without the option
// but for the banner's command line; a later run without it removes the file; refused with
// --functions, with --scalar float and by describe and base. The library built from it is
// tests/model/loaded_model_test.cpp.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::modelgen;
using test::read_text;

// `text` without its line that starts with `prefix`.
std::string without_line(const std::string& text, const std::string& prefix) {
  const std::size_t at = text.find("\n" + prefix);
  if (at == std::string::npos) return text;
  return text.substr(0, at) + text.substr(text.find('\n', at + 1));
}

TEST(ModelgenLoadable, WritesTheEntryPointAndListsWhatALibraryCompiles) {
  const fs::path folder = test::test_folder("loadable");
  const std::string robot = test::quoted_source("robots/tx40.yaml");
  ASSERT_EQ(modelgen(robot + " -o " + test::quoted(folder / "plain")).exit_code, 0);
  const CliRun run = modelgen(robot + " -o " + test::quoted(folder / "loadable") + " --loadable");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out + run.err, "");
  const std::string entry = read_text(folder / "loadable" / "tx40_loadable.cpp");
  EXPECT_NE(entry.find("// Regenerate: modelgen tx40.yaml -o <dir> --loadable\n"),
            std::string::npos);
  EXPECT_NE(entry.find("#include \"tx40.hpp\""), std::string::npos);
  EXPECT_NE(entry.find("modelgen_loadable_model_v1(void) {"), std::string::npos);
  const std::string manifest = read_text(folder / "loadable" / "tx40.json");
  EXPECT_NE(manifest.find("    \"tx40_loadable.cpp\",\n    \"tx40.json\"\n"), std::string::npos);
  // The tables, the table's functions and what they call (drive_regressor calls the standard
  // regressor), not the others.
  const std::size_t sources = manifest.find("\"loadable_sources\": [\n    \"tx40.cpp\",\n");
  ASSERT_NE(sources, std::string::npos) << manifest;
  const std::string list = manifest.substr(sources, manifest.find(']', sources) - sources);
  for (const char* file : {"tx40_idim_regressor_standard.cpp", "tx40_mass_matrix_and_bias.cpp",
                           "tx40_inverse_dynamics_state_jacobian.cpp",
                           "tx40_drive_torque_jacobian_given_regressor.cpp", "tx40_loadable.cpp"}) {
    EXPECT_NE(list.find(file), std::string::npos) << file;
  }
  for (const char* file : {"tx40_drive_torque_state_jacobian.cpp", "tx40_energy_regressor.cpp",
                           "tx40_idim_regressor_sincos.cpp"}) {
    EXPECT_EQ(list.find(file), std::string::npos) << file;
  }
  // Every other file: the same code, the banner's command line aside.
  for (const char* file : {"tx40.hpp", "tx40.cpp", "tx40_inverse_dynamics.cpp"}) {
    EXPECT_EQ(without_line(read_text(folder / "loadable" / file), "// Regenerate: "),
              without_line(read_text(folder / "plain" / file), "// Regenerate: "))
        << file;
  }
  // Generated again without --loadable: the entry point is gone with the option.
  ASSERT_EQ(modelgen(robot + " -o " + test::quoted(folder / "loadable")).exit_code, 0);
  EXPECT_FALSE(fs::exists(folder / "loadable" / "tx40_loadable.cpp"));
  EXPECT_EQ(read_text(folder / "loadable" / "tx40.json"),
            read_text(folder / "plain" / "tx40.json"));
}

TEST(ModelgenLoadable, IsRefusedWithoutEveryDoubleFunction) {
  const fs::path folder = test::test_folder("loadable");
  const std::string robot = test::quoted_source("robots/tx40.yaml") + " -o " + test::quoted(folder);
  const struct {
    std::string arguments, message;
  } cases[] = {
      {robot + " --loadable --functions inverse_dynamics",
       "modelgen: --loadable and --functions exclude each other (a loadable model needs every "
       "function the runtime calls)\n"},
      {robot + " --scalar float --loadable",
       "modelgen: --loadable needs the double entry points: use --scalar double or both\n"},
      {"describe " + test::quoted_source("robots/tx40.yaml") + " --loadable",
       "modelgen: describe takes no --loadable; it belongs to generation (-o DIR)\n"},
  };
  for (const auto& c : cases) {
    const CliRun run = modelgen(c.arguments);
    EXPECT_EQ(run.exit_code, 2) << c.arguments;
    EXPECT_EQ(run.err.substr(0, c.message.size()), c.message) << c.arguments;
  }
  EXPECT_FALSE(fs::exists(folder / "tx40.hpp"));
}

}  // namespace
}  // namespace modelgen
