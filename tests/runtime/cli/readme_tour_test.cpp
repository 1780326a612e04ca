// README's ten-line campaign runs as written: every `$B/modelgen ...` and `$B/modelid ...`
// of its "identification campaign" section, in order, from a folder where robots/ is the
// source tree's and build/ is empty, each exiting 0 and writing what the next one reads.

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

// The backquoted commands of the section, with B and D as its first line sets them.
std::vector<std::string> tour_commands() {
  const std::string readme = test::read_text(test::source_path("README.md"));
  const std::size_t start = readme.find("## An identification campaign");
  const std::size_t end = readme.find("\n## ", start + 1);
  EXPECT_NE(start, std::string::npos);
  const std::string section = readme.substr(start, end - start);
  std::vector<std::string> commands;
  const std::regex command(R"(`\$B/([^`]+)`)");
  for (auto it = std::sregex_iterator(section.begin(), section.end(), command);
       it != std::sregex_iterator(); ++it) {
    commands.push_back(std::regex_replace((*it)[1].str(), std::regex(R"(\$D/)"),
                                          "robots/data/tx40/"));
  }
  return commands;
}

TEST(ReadmeTour, EveryCommandRunsInOrder) {
  const std::vector<std::string> commands = tour_commands();
  ASSERT_GE(commands.size(), 10u);
  const fs::path dir = test::test_folder();
  fs::create_directories(dir / "build");
  fs::create_directory_symlink(test::source_path("robots"), dir / "robots");
  for (const std::string& line : commands) {
    const std::size_t blank = line.find(' ');
    const std::string program = line.substr(0, blank);
    ASSERT_TRUE(program == "modelgen" || program == "modelid") << line;
    const test::CliRun run =
        test::run_cli(program, line.substr(blank + 1), {.working_directory = dir});
    EXPECT_EQ(run.exit_code, 0) << line << "\n" << run.err;
  }
  // What the last steps hand on: the estimate, the identified description, firmware code.
  for (const char* made : {"build/cl_iv.json", "build/tx40_identified.yaml",
                           "build/tx40_fw/tx40_inverse_dynamics_identified.cpp",
                           "build/design.yaml"}) {
    EXPECT_TRUE(fs::exists(dir / made)) << made;
  }
}

}  // namespace
}  // namespace modelgen
