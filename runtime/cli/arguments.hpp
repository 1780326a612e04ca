// modelid's use of the shared command-line conventions (modelgen/model/command_line.hpp): the
// refusal of stray positional arguments, and the all-or-nothing file write every output goes
// through.
#pragma once

#include <string>

#include "modelgen/model/command_line.hpp"

namespace modelgen::internal {

/// Throws UsageError naming the first positional argument, for commands that take options
/// only (a data file given without --data would otherwise be ignored).
void reject_positional(const CommandLine& args);

/// The options of modelid's COMMAND (argv[1]) parsed from argv[2..argc).
inline CommandLine parse_arguments(int argc, char** argv,
                                   const std::map<std::string, OptionKind>& allowed) {
  return parse_command_line(argc, argv, 2, argv[1], allowed);
}

/// Writes `text` to `path` through a temporary file beside it and a rename, so the file is
/// either the old one or the whole new one, never a part. Throws std::runtime_error
/// "PATH: error: cannot write the file: REASON"; the previous file is then unchanged.
void write_file(const std::string& path, const std::string& text);

}  // namespace modelgen::internal
