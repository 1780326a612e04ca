// Child processes of modelid: the generator and the C++ compiler that turn a description into a
// loadable model (model_build.hpp), run through /bin/sh so that a CXX of several words ("ccache
// g++") works as it does in make, their output kept in a log file and never on the terminal.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace modelgen::internal {

/// `path` in single quotes for /bin/sh (a quote inside escaped).
std::string shell_quoted(const std::filesystem::path& path);

/// What a child gave: its exit status (127: the shell found no such program; 128 + N: killed
/// by signal N; -1: it could not be started).
struct ChildExit {
  int status = -1;
  bool ok() const { return status == 0; }
};

/// Runs every shell command of `commands`, at most `jobs` at a time, each with standard
/// output and error appended to `log` and standard input empty; waits for all. One exit per
/// command, in order.
std::vector<ChildExit> run_shell_commands(const std::vector<std::string>& commands,
                                          const std::filesystem::path& log, int jobs);

/// The first line `command` writes on standard output (its standard error discarded), empty
/// when it writes nothing or fails: a compiler's `--version`.
std::string first_output_line(const std::string& command);

}  // namespace modelgen::internal
