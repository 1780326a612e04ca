// The documentation's commands run as written. README's ten-line campaign: every `$B/modelgen`
// and `$B/modelid` of its section, in order. docs/: every ```sh block of every page, the blocks
// of a page in order in one folder (a later block reads what an earlier one wrote), as a shell
// runs them, with build/bin the build's programs and robots/ a copy of the source tree's (a
// command may write into it). Blocks that build the project (cmake) are CI's own command; a
// block that reads ../shared runs only where ../shared is.

#include <algorithm>
#include <cctype>
#include <cstdlib>
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

// A folder like a clone after the build: robots/ copied, build/ empty.
fs::path campaign_folder() {
  const fs::path dir = test::test_folder();
  fs::create_directories(dir / "build");
  fs::copy(test::source_path("robots"), dir / "robots", fs::copy_options::recursive);
  return dir;
}

// The backquoted `$B/...` commands of README's campaign section, $D as its first line sets it.
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
    commands.push_back(
        std::regex_replace((*it)[1].str(), std::regex(R"(\$D/)"), "robots/data/tx40/"));
  }
  return commands;
}

TEST(DocsCommands, ReadmeTourRunsInOrder) {
  const std::vector<std::string> commands = tour_commands();
  ASSERT_GE(commands.size(), 10u);
  const fs::path dir = campaign_folder();
  for (const std::string& line : commands) {
    const std::size_t blank = line.find(' ');
    const std::string program = line.substr(0, blank);
    ASSERT_TRUE(program == "modelgen" || program == "modelid") << line;
    const test::CliRun run =
        test::run_cli(program, line.substr(blank + 1), {.working_directory = dir});
    EXPECT_EQ(run.exit_code, 0) << line << "\n" << run.err;
  }
  // What the last steps hand on: the estimate, the identified description, firmware code.
  for (const char* made :
       {"build/cl_iv.json", "build/tx40_identified.yaml",
        "build/tx40_fw/tx40_inverse_dynamics_identified.cpp", "build/design.yaml"}) {
    EXPECT_TRUE(fs::exists(dir / made)) << made;
  }
}

// The ```sh blocks of a Markdown page, in order.
std::vector<std::string> shell_blocks(const std::string& page) {
  const std::string text = test::read_text(test::source_path(page));
  std::vector<std::string> blocks;
  for (std::size_t at = text.find("```sh\n"); at != std::string::npos;
       at = text.find("```sh\n", at)) {
    const std::size_t body = at + 6, end = text.find("```", body);
    blocks.push_back(text.substr(body, end - body));
    at = end + 3;
  }
  return blocks;
}

// `text` with every `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at)) {
    text.replace(at, from.size(), to);
    at += to.size();
  }
  return text;
}

class DocsPage : public testing::TestWithParam<std::string> {};

TEST_P(DocsPage, ShellBlocksRunAsWritten) {
  const std::vector<std::string> blocks = shell_blocks(GetParam());
  ASSERT_FALSE(blocks.empty()) << GetParam() << " has no ```sh block any more";
  const fs::path dir = campaign_folder();
  const fs::path bin = fs::path(test::executable_path("modelid")).parent_path();
  int run = 0;
  for (const std::string& block : blocks) {
    if (block.find("cmake ") != std::string::npos) continue;  // building: CI's own command
    const bool reads_shared = block.find("../shared/") != std::string::npos;
    if (reads_shared && !fs::exists(test::shared_path("datasets"))) continue;
    std::string script = replaced(block, "build/bin", bin.string());
    script = replaced(script, "../shared/", test::shared_path("") + "/");
    test::write_text(dir / "block.sh", "set -e\n" + script);
    const std::string command =
        "cd " + test::quoted(dir) + " && sh block.sh >block.out 2>block.err";
    const int status = std::system(command.c_str());
    EXPECT_EQ(status, 0) << GetParam() << ":\n"
                         << block << "\n"
                         << test::read_text(dir / "block.err");
    ++run;
  }
  EXPECT_GT(run, 0) << GetParam() << ": every block was skipped";
}

INSTANTIATE_TEST_SUITE_P(EveryPageWithCommands, DocsPage,
                         testing::Values("docs/tutorial.md", "docs/real-data.md",
                                         "docs/commands/simulate.md"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

TEST(DocsCommands, EveryPageWithAShellBlockIsRun) {
  // A page that gains a block must join the list above.
  const std::vector<std::string> listed = {"docs/tutorial.md", "docs/real-data.md",
                                           "docs/commands/simulate.md"};
  for (const auto& entry : fs::recursive_directory_iterator(test::source_path("docs"))) {
    if (entry.path().extension() != ".md") continue;
    const std::string page =
        "docs/" + fs::relative(entry.path(), test::source_path("docs")).string();
    bool runnable = false;
    for (const std::string& block : shell_blocks(page)) {
      runnable = runnable || block.find("cmake ") == std::string::npos;
    }
    EXPECT_TRUE(!runnable || std::find(listed.begin(), listed.end(), page) != listed.end())
        << page << " has commands no test runs";
  }
}

}  // namespace
}  // namespace modelgen
