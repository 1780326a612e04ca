// Every broken input under tests/bad_inputs/<folder>/ is one case:
//
//   <folder>/command         the command lines to run on each input of the folder, one a line
//                            ('#' starts a comment line), with {input} (the input's path
//                            relative to the source tree) and {output} (an output folder that
//                            must stay untouched)
//   <folder>/<case>.<ext>    the broken input
//   <folder>/<case>.expected "exit <code>" on its first line, then the exact standard error
//
// Each command runs from the top of the source tree, so messages name the input as
// tests/bad_inputs/<folder>/<case>.<ext>, exactly as the .expected file spells it. Every
// command line must give that exit code and that standard error, print nothing on standard
// output and leave the output folder as it was. A case of "exit 0" is an input that is worth a
// warning but not a refusal: its standard error must be exactly the warning, its standard
// output is not compared, and the output folder must still hold what it had (the command's own
// outputs may join it). Folders without a `command` file hold what the commands use
// (tests/bad_inputs/robots/). Cases that cannot be files (a missing file) follow at the end.

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/cli_runner.hpp"
#include "tests/support/test_support.hpp"

namespace modelgen {
namespace {

namespace fs = std::filesystem;

constexpr const char* kCasesFolder = "tests/bad_inputs";

struct BadInput {
  std::string folder;  // "yaml"
  std::string file;    // "unknown_key.yaml"

  std::string input() const { return std::string(kCasesFolder) + "/" + folder + "/" + file; }
  std::string expected() const {
    return std::string(kCasesFolder) + "/" + folder + "/" + fs::path(file).stem().string() +
           ".expected";
  }
};

// How GoogleTest names a case in its output and CTest's test list.
void PrintTo(const BadInput& bad, std::ostream* out) { *out << bad.input(); }

/// The command lines of a `command` file: its lines but empty ones and '#' comments.
std::vector<std::string> command_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  }
  return lines;
}

/// Folders that hold cases: those with a `command` file, sorted.
std::vector<fs::path> case_folders() {
  std::vector<fs::path> folders;
  for (const auto& entry : fs::directory_iterator(test::source_path(kCasesFolder))) {
    if (entry.is_directory() && fs::exists(entry.path() / "command")) {
      folders.push_back(entry.path());
    }
  }
  std::sort(folders.begin(), folders.end());
  return folders;
}

/// The cases tests/CMakeLists.txt found: "<folder>/<file>", comma-separated (a new file there
/// reconfigures the build, which recompiles this test with the new list).
std::vector<BadInput> all_cases() {
  std::vector<BadInput> cases;
  std::istringstream list(MODELGEN_BAD_INPUT_CASES);
  for (std::string entry; std::getline(list, entry, ',');) {
    const std::size_t slash = entry.find('/');
    cases.push_back({entry.substr(0, slash), entry.substr(slash + 1)});
  }
  return cases;
}

std::string case_name(const testing::TestParamInfo<BadInput>& info) {
  std::string name = info.param.folder + "_" + fs::path(info.param.file).stem().string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

/// `text` with every `{name}` replaced by `value`.
std::string substitute(std::string text, const std::string& name, const std::string& value) {
  for (std::size_t at = text.find(name); at != std::string::npos;
       at = text.find(name, at + value.size())) {
    text.replace(at, name.size(), value);
  }
  return text;
}

class BadInputFile : public testing::TestWithParam<BadInput> {};

TEST_P(BadInputFile, ExitsWithTheExpectedMessage) {
  const BadInput& bad = GetParam();
  const std::string expected_path = test::source_path(bad.expected());
  ASSERT_TRUE(fs::exists(expected_path))
      << bad.input() << " has no expected file: write " << bad.expected()
      << " with \"exit <code>\" on its first line and the exact standard error after it";
  const std::string expected = test::read_text(expected_path);
  const std::size_t first_end = expected.find('\n');
  const std::string first_line = expected.substr(0, first_end);
  ASSERT_EQ(first_line.rfind("exit ", 0), 0u)
      << bad.expected() << ": the first line must be \"exit <code>\", not '" << first_line << "'";
  const int exit_code = std::stoi(first_line.substr(5));
  const std::string expected_err =
      first_end == std::string::npos ? std::string() : expected.substr(first_end + 1);

  const std::string source_folder = std::string(kCasesFolder) + "/" + bad.folder;
  const std::vector<std::string> commands =
      command_lines(test::read_text(test::source_path(source_folder + "/command")));
  ASSERT_FALSE(commands.empty()) << source_folder << "/command has no command line";
  for (const std::string& line : commands) {
    const fs::path output = test::test_folder("bad_input");
    const std::string kept = "what the user had\n";
    test::write_text(output / "kept.txt", kept);
    const std::string command = substitute(substitute(line, "{input}", test::quoted(bad.input())),
                                           "{output}", test::quoted(output));
    const std::size_t space = command.find(' ');
    const test::CliRun run = test::run_cli(command.substr(0, space), command.substr(space + 1),
                                           {.working_directory = test::source_path("")});
    SCOPED_TRACE("(cd <source tree> && " + command + ")");
    EXPECT_EQ(run.exit_code, exit_code);
    EXPECT_EQ(run.err, expected_err);
    const bool warning = exit_code == 0;
    if (!warning) {
      EXPECT_EQ(run.out, "");
    }
    std::vector<std::string> left;
    for (const auto& entry : fs::directory_iterator(output)) {
      left.push_back(entry.path().filename().string());
    }
    if (!warning) {
      EXPECT_EQ(left, std::vector<std::string>{"kept.txt"}) << "the output folder was changed";
    }
    EXPECT_EQ(test::read_text(output / "kept.txt"), kept);
  }
}

INSTANTIATE_TEST_SUITE_P(Files, BadInputFile, testing::ValuesIn(all_cases()), case_name);

// The folders as they are now against the list compiled in: a stale build would skip a case.
TEST(BadInputFolders, EveryFileIsACaseOrTheMessageOfOne) {
  std::vector<std::string> inputs;
  for (const BadInput& bad : all_cases()) inputs.push_back(bad.folder + "/" + bad.file);
  for (const fs::path& folder : case_folders()) {
    for (const auto& entry : fs::directory_iterator(folder)) {
      const fs::path& path = entry.path();
      const std::string relative = folder.filename().string() + "/" + path.filename().string();
      if (path.filename() == "command" || path.filename().string()[0] == '.') continue;
      if (path.extension() != ".expected") {
        EXPECT_TRUE(std::find(inputs.begin(), inputs.end(), relative) != inputs.end())
            << relative << " is not among the cases this test was built with; rebuild";
        continue;
      }
      bool has_input = false;
      for (const auto& other : fs::directory_iterator(folder)) {
        has_input |= other.path().stem() == path.stem() && other.path().extension() != ".expected";
      }
      EXPECT_TRUE(has_input) << relative << " is the message of an input that is not there";
    }
  }
}

// Not files: a description that does not exist, and one of no known format.

TEST(BadInputs, MissingDescription) {
  const test::CliRun run = test::modelgen("describe robots/no_such_robot.yaml",
                                          {.working_directory = test::source_path("")});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.err,
            "robots/no_such_robot.yaml: error: cannot open the file (does it exist and is it "
            "readable?)\n");
  EXPECT_EQ(run.out, "");
}

TEST(BadInputs, DescriptionOfUnknownFormat) {
  const test::CliRun run =
      test::modelgen("describe README.md", {.working_directory = test::source_path("")});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.err,
            "README.md: error: unknown description format '.md': expected .yaml/.yml "
            "(modified DH) or .urdf\n");
  EXPECT_EQ(run.out, "");
}

// A folder or a missing file where an experiment's YAML is expected: the same message style as
// for a description, never the stream library's "basic_filebuf::underflow".
TEST(BadInputs, FolderOrMissingFileAsControllerOrTrajectory) {
  const std::string simulate =
      "simulate --robot tests/bad_inputs/robots/two_axes.yaml --params "
      "tests/bad_inputs/robots/two_axes_params.json --ignore-limits -o /nonexistent/out.csv ";
  const std::string trajectory = "--trajectory tests/bad_inputs/robots/two_axes_trajectory.yaml ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {simulate + "--trajectory tests/bad_inputs",
       "tests/bad_inputs: error: is a directory, "
       "not a trajectory file\n"},
      {simulate + trajectory + "--controller tests/bad_inputs",
       "tests/bad_inputs: error: is a directory, not a controller file\n"},
      {simulate + "--trajectory tests/no_such.yaml",
       "tests/no_such.yaml: error: cannot open the file (does it exist and is it readable?)\n"},
      {simulate + trajectory + "--controller tests/no_such.yaml",
       "tests/no_such.yaml: error: cannot open the file (does it exist and is it readable?)\n"}};
  for (const auto& [arguments, message] : cases) {
    const test::CliRun run = test::modelid(arguments, {.working_directory = test::source_path("")});
    EXPECT_EQ(run.exit_code, 1) << arguments;
    EXPECT_NE(run.err.find(message), std::string::npos) << arguments << "\n" << run.err;
    EXPECT_EQ(run.err.find("basic_filebuf"), std::string::npos) << run.err;
  }
}

}  // namespace
}  // namespace modelgen
