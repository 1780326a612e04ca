// The one way tests run the built command-line tools (modelgen, modelid) as a user would: a
// shell command line, standard output and standard error captured, the exit code kept.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace modelgen::test {

/// What a run of a command-line tool gave.
struct CliRun {
  int exit_code = -1;  // the exit status; 128 + signal number when the tool was killed
  std::string out, err;
};

/// Where and how to run a tool.
struct CliOptions {
  /// Working directory of the run; empty: the test's own.
  std::filesystem::path working_directory;
};

/// Runs the built `program` ("modelgen" or "modelid") with `arguments`, a shell command-line
/// tail (quote paths with quoted()), standard input empty. Output goes to files under
/// testing::TempDir() named after the running test and this process, so tests run in parallel.
CliRun run_cli(std::string_view program, const std::string& arguments,
               const CliOptions& options = {});

/// The build's modelgen and modelid executables.
inline CliRun modelgen(const std::string& arguments, const CliOptions& options = {}) {
  return run_cli("modelgen", arguments, options);
}
inline CliRun modelid(const std::string& arguments, const CliOptions& options = {}) {
  return run_cli("modelid", arguments, options);
}

/// Absolute path of a built executable of the project ("modelgen", "modelid").
std::string executable_path(std::string_view program);

/// A path in single quotes for the shell (a single quote inside is escaped).
std::string quoted(const std::filesystem::path& path);

/// A file of the source tree, absolute and quoted: quoted_source("robots/tx40.yaml").
std::string quoted_source(std::string_view relative);

/// The bytes of a file ("" when it cannot be read).
std::string read_text(const std::filesystem::path& path);

/// Writes `text` to `path`, replacing it.
void write_text(const std::filesystem::path& path, const std::string& text);

/// A folder of its own for the running test (or, in SetUpTestSuite, for the suite), emptied
/// first and removed when the process exits: TempDir()/<prefix>_<suite>_<test>_<pid>
/// (characters other than letters, digits, '_' and '-' become '_').
std::filesystem::path test_folder(std::string_view prefix = "cli");

}  // namespace modelgen::test
