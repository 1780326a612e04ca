// The command tables as a user meets them: `modelid COMMAND --help` and `modelgen [COMMAND]
// --help` for every command, each listing exactly the options its reference page
// (docs/commands/COMMAND.md, written by hand) lists; did-you-mean for a mistyped command,
// option or value; usage errors that show the command's own usage.

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

using test::CliRun;
using test::modelgen;
using test::modelid;

// The options in the first column of the "## Options" table of a reference page.
std::set<std::string> documented_options(const std::string& page) {
  std::ifstream in(test::source_path("docs/commands/" + page));
  EXPECT_TRUE(in) << page;
  std::set<std::string> options;
  bool in_options = false;
  const std::regex row(R"(^\| `(-[-a-z]+|-o)` \|)");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("## ", 0) == 0) in_options = line == "## Options";
    std::smatch match;
    if (in_options && std::regex_search(line, match, row)) options.insert(match[1]);
  }
  return options;
}

// The options a --help text lists: lines that start with two blanks and a dash.
std::set<std::string> helped_options(const std::string& help) {
  std::set<std::string> options;
  std::istringstream in(help);
  const std::regex row(R"(^  (-[-a-z]+|-o)( |$))");
  for (std::string line; std::getline(in, line);) {
    std::smatch match;
    if (std::regex_search(line, match, row)) options.insert(match[1]);
  }
  return options;
}

class ModelidCommandHelp : public testing::TestWithParam<std::string> {};

TEST_P(ModelidCommandHelp, ListsTheOptionsOfItsReferencePage) {
  const std::string& command = GetParam();
  const CliRun run = modelid(command + " --help");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out.rfind("usage: modelid " + command, 0), 0u) << run.out;
  EXPECT_EQ(helped_options(run.out), documented_options(command + ".md")) << run.out;
  // --help anywhere on the line wins over the other options, right or wrong.
  EXPECT_EQ(modelid(command + " --robot tx40 --help").exit_code, 0);
}

INSTANTIATE_TEST_SUITE_P(EveryCommand, ModelidCommandHelp,
                         testing::Values("fit", "predict", "simulate", "validate", "export",
                                         "design", "check-trajectory", "check"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

TEST(ModelidUsage, ListsEveryCommandWithItsRequiredOptions) {
  const CliRun run = modelid("--help");
  ASSERT_EQ(run.exit_code, 0);
  for (const char* line : {"modelid fit --robot ROBOT --data FILE... --method METHOD [OPTIONS]",
                           "modelid predict --robot ROBOT --params EST.json --data FILE... "
                           "[OPTIONS]",
                           "modelid check ROBOT [OPTIONS]", "modelid design --robot ROBOT"}) {
    EXPECT_NE(run.out.find(line), std::string::npos) << line << "\n" << run.out;
  }
}

TEST(ModelgenHelp, ListsTheOptionsOfItsReferencePage) {
  std::set<std::string> helped;
  for (const char* command : {"", "describe ", "base "}) {
    const CliRun run = modelgen(std::string(command) + "--help");
    ASSERT_EQ(run.exit_code, 0) << command << run.err;
    const std::set<std::string> options = helped_options(run.out);
    helped.insert(options.begin(), options.end());
  }
  std::set<std::string> documented = documented_options("modelgen.md");
  // The program's own switches, taken alone, are not options of a command.
  for (const char* alone : {"--list-functions", "--version", "--help"}) documented.erase(alone);
  EXPECT_EQ(helped, documented);
}

TEST(ModelidUsageErrors, NameTheClosestCommandOptionOrValue) {
  const CliRun command = modelid("fti --robot tx40");
  EXPECT_EQ(command.exit_code, 2);
  EXPECT_NE(command.err.find("unknown command 'fti' (did you mean 'fit'?)"), std::string::npos)
      << command.err;

  const CliRun option = modelid("fit --robot tx40 --data a.csv --metod wls");
  EXPECT_EQ(option.exit_code, 2);
  EXPECT_NE(option.err.find("unknown option '--metod' for fit (did you mean '--method'?)"),
            std::string::npos)
      << option.err;
  // The command's own usage follows, not the whole program's.
  EXPECT_NE(option.err.find("usage: modelid fit --robot ROBOT"), std::string::npos) << option.err;
  EXPECT_EQ(option.err.find("modelid simulate"), std::string::npos) << option.err;

  const CliRun value = modelid("fit --robot tx40 --data a.csv --method wsl");
  EXPECT_EQ(value.exit_code, 2);
  EXPECT_NE(value.err.find("--method must be ols, wls, pim-wls, iv, didim, pm, ml or ml-eiv, "
                           "not 'wsl' (did you mean 'wls'?)"),
            std::string::npos)
      << value.err;

  const CliRun hold =
      modelid("predict --robot tx40 --params e.json --data a.csv --torque-hold zho");
  EXPECT_EQ(hold.exit_code, 2);
  EXPECT_NE(hold.err.find("did you mean 'zoh'?"), std::string::npos) << hold.err;

  const CliRun generator = modelgen("robots/tx40.yaml -o out --scalr float");
  EXPECT_EQ(generator.exit_code, 2);
  EXPECT_NE(generator.err.find("unknown option '--scalr' (did you mean '--scalar'?)"),
            std::string::npos)
      << generator.err;
}

}  // namespace
}  // namespace modelgen
