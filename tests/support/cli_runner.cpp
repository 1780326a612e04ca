// Implementation of the command-line test runner: std::system with redirections to files.

#include "tests/support/cli_runner.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <gtest/gtest.h>

namespace modelgen::test {

namespace fs = std::filesystem;

namespace {

std::string safe_name(std::string text) {
  for (char& c : text) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '_' || c == '-';
    if (!keep) c = '_';
  }
  return text;
}

/// "<suite>_<test>" of the running test, "<suite>" in a suite's set-up, or "no_test" outside
/// both.
std::string current_test_name() {
  const testing::UnitTest& unit = *testing::UnitTest::GetInstance();
  if (const testing::TestInfo* info = unit.current_test_info()) {
    return safe_name(std::string(info->test_suite_name()) + "_" + info->name());
  }
  if (const testing::TestSuite* suite = unit.current_test_suite()) {
    return safe_name(suite->name());
  }
  return "no_test";
}

/// Removes the folders test_folder handed out when the test process ends: their names carry the
/// process id, so nothing else would ever reuse or remove them. Only in that process: a forked
/// child (a death test) that exits must not remove its parent's folders.
class FolderJanitor {
 public:
  void remove_at_exit(const fs::path& dir) { folders_.push_back(dir); }
  ~FolderJanitor() {
    if (::getpid() != owner_) return;
    for (const fs::path& dir : folders_) {
      std::error_code ignored;
      fs::remove_all(dir, ignored);
    }
  }

 private:
  std::vector<fs::path> folders_;
  const pid_t owner_ = ::getpid();
};

FolderJanitor& janitor() {
  static FolderJanitor instance;
  return instance;
}

}  // namespace

std::string executable_path(std::string_view program) {
  if (program == "modelgen") return MODELGEN_MODELGEN_EXECUTABLE;
  if (program == "modelid") return MODELGEN_MODELID_EXECUTABLE;
  throw std::invalid_argument("run_cli: no executable '" + std::string(program) + "'");
}

CliRun run_cli(std::string_view program, const std::string& arguments, const CliOptions& options) {
  const fs::path stem =
      fs::path(testing::TempDir()) /
      (std::string(program) + "_" + current_test_name() + "_" + std::to_string(::getpid()));
  const fs::path out = stem.string() + ".out", err = stem.string() + ".err";
  std::string command;
  if (!options.working_directory.empty()) {
    command = "cd " + test::quoted(options.working_directory) + " && ";
  }
  command += test::quoted(executable_path(program)) + " " + arguments + " </dev/null >" +
             test::quoted(out) + " 2>" + test::quoted(err);
  const int status = std::system(command.c_str());
  CliRun run;
  if (status != -1 && WIFEXITED(status)) {
    run.exit_code = WEXITSTATUS(status);
  } else if (status != -1 && WIFSIGNALED(status)) {
    run.exit_code = 128 + WTERMSIG(status);
  }
  run.out = read_text(out);
  run.err = read_text(err);
  fs::remove(out);
  fs::remove(err);
  return run;
}

std::string quoted(const fs::path& path) {
  std::string text = "'";
  for (const char c : path.string()) {
    if (c == '\'') {
      text += "'\\''";
    } else {
      text += c;
    }
  }
  return text + "'";
}

std::string quoted_source(std::string_view relative) {
  return test::quoted(std::string(MODELGEN_SOURCE_DIR) + "/" + std::string(relative));
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

fs::path test_folder(std::string_view prefix) {
  // The process id keeps apart ctest's parallel processes, which each run one test of a suite
  // and may share a suite-level folder name.
  const fs::path dir = fs::path(testing::TempDir()) / (std::string(prefix) + "_" +
                                                       current_test_name() + "_" +
                                                       std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  janitor().remove_at_exit(dir);
  return dir;
}

}  // namespace modelgen::test
