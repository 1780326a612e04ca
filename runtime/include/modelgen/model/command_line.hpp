// The command-line conventions modelgen and modelid share: options that take one value, repeat
// or are flags, positional arguments, strict numbers, and the usage error both programs print
// with their usage before exiting with 2.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "modelgen/model/error.hpp"

namespace modelgen {

/// A bad command line (unknown option, missing value, malformed number): the program prints
/// the message and its usage and exits with 2.
class UsageError : public Error {
 public:
  using Error::Error;
};

enum class OptionKind {
  kOnce,      ///< takes a value, at most once
  kRepeated,  ///< takes a value, any number of times (--data A --data B)
  kFlag,      ///< takes no value (--essential)
};

struct CommandLine {
  std::string command;  ///< the subcommand, for messages ("fit needs --robot"); may be empty
  std::vector<std::string> positional;
  /// The values of each option given, in command-line order; a flag holds one empty value.
  std::map<std::string, std::vector<std::string>> options;

  bool has(const std::string& name) const { return options.count(name) > 0; }
  /// The value of an option given once; UsageError if it is missing or repeated.
  const std::string& one(const std::string& name) const;
  /// The value of an option given at most once, or `fallback`.
  std::string one_or(const std::string& name, const std::string& fallback) const;
  /// Every value of a repeated option; empty if it was not given.
  const std::vector<std::string>& all(const std::string& name) const;
};

/// Parses argv[first..argc): anything starting with '-' must be one of `allowed`, and a kOnce
/// or kRepeated option consumes the next argument as its value; the rest is positional.
/// `command` names the subcommand in messages. Throws UsageError for an unknown option, a
/// missing value or a kOnce/kFlag option given twice.
CommandLine parse_command_line(int argc, char** argv, int first, const std::string& command,
                               const std::map<std::string, OptionKind>& allowed);

/// A finite number in the whole of `text` (from_chars syntax); UsageError naming `option`
/// otherwise.
double parse_number(const std::string& text, const std::string& option);

/// The comma-separated items of an option's value ("3,4,5"). UsageError naming `option` for an
/// empty value or an empty item (",,", a trailing comma): it is a typo, never "nothing".
std::vector<std::string> comma_items(const std::string& text, const std::string& option);

/// What a per-axis number may be.
enum class AxisValue { kNonNegative, kPositive };

/// One number per axis from "V" (every axis) or "V1,...,Vn" (n = `count`), for options such as
/// --noise or --min-speed. UsageError naming `option`, `what` ("standard deviation") and
/// `axes` ("joint", "motor") for an item that is not a number or breaks `rule`, or a count
/// that is neither 1 nor `count`.
std::vector<double> per_axis_values(const std::string& text, const std::string& option, int count,
                                    const std::string& what, const std::string& axes,
                                    AxisValue rule);

/// The value of --angle-tolerance RAD (LoadOptions::angle_tolerance) when given, else the
/// default; UsageError unless 0 <= RAD < 0.7 (beyond pi/4 every angle would be near some
/// quarter turn).
double angle_tolerance_option(const CommandLine& line);

}  // namespace modelgen
