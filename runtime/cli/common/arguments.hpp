// The all-or-nothing file write every output of modelid goes through, and the command-line
// conventions it shares with modelgen (modelgen/model/command_line.hpp).
#pragma once

#include <string>

#include "modelgen/model/command_line.hpp"

namespace modelgen::internal {

/// Writes `text` to `path` through a temporary file beside it and a rename, so the file is
/// either the old one or the whole new one, never a part. Throws std::runtime_error
/// "PATH: error: cannot write the file: REASON"; the previous file is then unchanged.
void write_file(const std::string& path, const std::string& text);

}  // namespace modelgen::internal
