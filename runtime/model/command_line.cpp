// Option parsing shared by modelgen and modelid.

#include "modelgen/model/command_line.hpp"

#include "modelgen/model/load_robot.hpp"

#include <charconv>
#include <cmath>

namespace modelgen {

const std::string& CommandLine::one(const std::string& name) const {
  auto found = options.find(name);
  if (found == options.end()) {
    throw UsageError((command.empty() ? std::string("missing ") : command + " needs ") + name);
  }
  if (found->second.size() != 1) throw UsageError(name + " given more than once");
  return found->second.front();
}

std::string CommandLine::one_or(const std::string& name, const std::string& fallback) const {
  return has(name) ? one(name) : fallback;
}

const std::vector<std::string>& CommandLine::all(const std::string& name) const {
  static const std::vector<std::string> kNone;
  auto found = options.find(name);
  return found == options.end() ? kNone : found->second;
}

CommandLine parse_command_line(int argc, char** argv, int first, const std::string& command,
                               const std::map<std::string, OptionKind>& allowed) {
  CommandLine line;
  line.command = command;
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() > 1 && arg[0] == '-') {
      auto found = allowed.find(arg);
      if (found == allowed.end()) {
        throw UsageError("unknown option '" + arg + "'" + (command.empty() ? "" : " for " + command));
      }
      std::vector<std::string>& values = line.options[arg];
      if (found->second == OptionKind::kFlag) {
        values.emplace_back();
      } else {
        if (i + 1 >= argc) throw UsageError(arg + " needs a value");
        values.push_back(argv[++i]);
      }
      if (found->second != OptionKind::kRepeated && values.size() > 1) {
        throw UsageError(arg + " given twice");
      }
    } else {
      line.positional.push_back(arg);
    }
  }
  return line;
}

double parse_number(const std::string& text, const std::string& option) {
  double value = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw UsageError(option + " must be a number, not '" + text + "'");
  }
  return value;
}

std::vector<std::string> comma_items(const std::string& text, const std::string& option) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::size_t end = comma == std::string::npos ? text.size() : comma;
    if (end == start) throw UsageError(option + ": empty item in '" + text + "'");
    items.push_back(text.substr(start, end - start));
    if (comma == std::string::npos) return items;
    start = comma + 1;
  }
}

std::vector<double> per_axis_values(const std::string& text, const std::string& option, int count,
                                    const std::string& what, const std::string& axes,
                                    AxisValue rule) {
  std::vector<double> values;
  for (const std::string& item : comma_items(text, option)) {
    const double value = parse_number(item, option);
    if (rule == AxisValue::kNonNegative && !(value >= 0)) {
      throw UsageError(option + ": a " + what + " cannot be negative, not '" + item + "'");
    }
    if (rule == AxisValue::kPositive && !(value > 0)) {
      throw UsageError(option + ": a " + what + " must be positive, not '" + item + "'");
    }
    values.push_back(value);
  }
  if (values.size() == 1) values.assign(static_cast<std::size_t>(count), values.front());
  if (static_cast<int>(values.size()) != count) {
    throw UsageError(option + " needs one " + what + " or " + std::to_string(count) + " (one per " +
                     axes + "), not " + std::to_string(values.size()) + ": '" + text + "'");
  }
  return values;
}

double angle_tolerance_option(const CommandLine& line) {
  if (!line.has("--angle-tolerance")) return kDefaultAngleTolerance;
  const std::string& text = line.one("--angle-tolerance");
  const double tolerance = parse_number(text, "--angle-tolerance");
  if (!(tolerance >= 0 && tolerance < 0.7)) {
    throw UsageError("--angle-tolerance must be between 0 and 0.7 rad, not '" + text + "'");
  }
  return tolerance;
}

}  // namespace modelgen
