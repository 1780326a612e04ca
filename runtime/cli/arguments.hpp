// The command line of modelid: options per command (single, repeated or flag), strict numbers,
// the usage error type, and the all-or-nothing file write every output goes through.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace modelgen::internal {

/// A bad command line (unknown option, missing value, malformed number): main prints the
/// message and the usage and exits with 2.
struct UsageError {
  std::string message;
};

enum class OptionKind {
  kOnce,      ///< takes a value, at most once
  kRepeated,  ///< takes a value, any number of times (--data A --data B)
  kFlag,      ///< takes no value (--essential)
};

struct Arguments {
  std::string command;
  std::vector<std::string> positional;
  /// The values of each option given, in command-line order; a flag holds one empty value.
  std::map<std::string, std::vector<std::string>> options;

  bool has(const std::string& name) const { return options.count(name) > 0; }
  /// The value of an option given once; UsageError if it is missing or repeated.
  const std::string& one(const std::string& name) const;
  /// Every value of a repeated option; empty if it was not given.
  const std::vector<std::string>& all(const std::string& name) const;
};

/// Parses argv[2..argc) for the command argv[1]: anything starting with '-' must be one of
/// `allowed`, and a kOnce or kRepeated option consumes the next argument as its value.
/// Throws UsageError for an unknown option, a missing value or a kOnce/kFlag option given twice.
/// Throws UsageError naming the first positional argument, for commands that take options
/// only (a data file given without --data would otherwise be ignored).
void reject_positional(const Arguments& args);

Arguments parse_arguments(int argc, char** argv, const std::map<std::string, OptionKind>& allowed);

/// A finite number in the whole of `text` (from_chars syntax); UsageError naming `option`
/// otherwise.
double parse_number(const std::string& text, const std::string& option);

/// Writes `text` to `path` through a temporary file beside it and a rename, so the file is
/// either the old one or the whole new one, never a part. Throws std::runtime_error
/// "PATH: error: cannot write the file: REASON"; the previous file is then unchanged.
void write_file(const std::string& path, const std::string& text);

}  // namespace modelgen::internal
