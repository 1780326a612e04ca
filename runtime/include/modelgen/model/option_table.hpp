// Commands declared as tables: each command of modelgen and modelid lists its options once
// (name, value type, unit, default, allowed values, the methods that use it, help text), and
// parsing, type and range checks, mutual exclusions, `PROGRAM COMMAND --help`, the programs'
// usage text and the did-you-mean of a mistyped option or value all come from that table.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "modelgen/model/command_line.hpp"

namespace modelgen {

/// What an option's value must be; the parser checks it before the command runs.
enum class ValueType {
  kFlag,         ///< no value
  kText,         ///< any text: a file, a name, a list the command reads itself
  kNumber,       ///< a finite number
  kPositive,     ///< a finite number above 0
  kNonNegative,  ///< a finite number of at least 0
  kCount,        ///< a whole number of at least 1
  kWhole,        ///< a whole number of at least 0
  kChoice,       ///< one of OptionSpec::choices
};

struct OptionSpec {
  std::string name{};  ///< "--method", "-o"
  ValueType type = ValueType::kText;
  std::string value{};  ///< the value's placeholder in help and usage ("FILE", "HZ"); kFlag: empty
  std::string help{};   ///< what it does, one or two sentences
  std::string unit{};   ///< of a number ("Hz", "s", "rad"); empty when it has none
  std::string default_value{};         ///< shown in help; empty when there is none
  bool repeatable = false;             ///< --data A --data B
  bool required = false;               ///< the command cannot run without it
  std::vector<std::string> choices{};  ///< kChoice: the allowed values, in the order shown
  /// The values of the command's selector (CommandSpec::selector) that use this option; empty
  /// when every value does.
  std::vector<std::string> methods{};
  /// Another option this one refines ("--r-sigma" needs "--essential"); empty for none.
  std::string needs{};
  std::string group{};  ///< help section ("data preparation"); empty for the command's own
};

/// Two options that cannot be given together, and why (said in the message when not empty).
struct Exclusion {
  std::string first{}, second{};
  std::string reason{};
};

/// Selector values that share a name in messages ("the closed-loop methods": iv, didim).
struct MethodFamily {
  std::string name{};
  std::vector<std::string> methods{};
};

struct CommandSpec {
  std::string program{};   ///< "modelid"
  std::string name{};      ///< "fit"; empty for a program without commands
  std::string summary{};   ///< one line, for the program's usage
  std::string operands{};  ///< positional operands in usage ("ROBOT"); empty: none allowed
  /// The option whose value picks a variant of the command ("--method"); empty for none.
  std::string selector{};
  std::vector<MethodFamily> families{};  ///< for messages about the selector's values
  std::vector<OptionSpec> options{};
  std::vector<Exclusion> exclusive{};  ///< pairs of options that cannot be given together
  /// Options of sibling commands and where they belong ("--params", "generation (-o DIR)"):
  /// refused with that hint rather than as unknown.
  std::vector<std::pair<std::string, std::string>> elsewhere{};
  std::string details{};  ///< text after the options in --help (formats, notes); may be empty

  const OptionSpec* find(const std::string& option) const;
};

/// Parses argv[first..argc) by `spec`: every option must be in the table (an unknown one names
/// the closest), takes a value unless it is a flag, appears once unless repeatable; values are
/// checked against their type and choices; options of other selector values than the one
/// given, options whose `needs` is missing, exclusive pairs, positional arguments where none
/// are allowed and missing required options are refused. Throws UsageError with messages that
/// name the option and what is wrong.
CommandLine parse_command(const CommandSpec& spec, int argc, char** argv, int first);

/// True when argv[first..argc) asks for help (--help or -h).
bool asks_for_help(int argc, char** argv, int first);

/// `PROGRAM COMMAND --help`: the usage line, the summary, the options by group with their
/// value, unit, default, allowed values and methods, then the details.
std::string command_help(const CommandSpec& spec);

/// One line of the program's usage: "modelid fit --robot ROBOT --data FILE... --method M
/// [OPTIONS]" (required options spelled out, the rest as [OPTIONS]).
std::string usage_line(const CommandSpec& spec);

/// `text` wrapped at 96 columns, its first line starting at `column`, the others indented by
/// `indent`; each line of `text` starts a new paragraph.
std::string wrapped(const std::string& text, std::size_t column, std::size_t indent);

/// "a, b or c".
std::string or_list(const std::vector<std::string>& words);

}  // namespace modelgen
