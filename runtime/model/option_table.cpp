// Parsing a command line by its command's option table (modelgen/model/option_table.hpp):
// the options are read, then each check the table implies runs as its own step.

#include "modelgen/model/option_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace modelgen {

const OptionSpec* CommandSpec::find(const std::string& option) const {
  for (const OptionSpec& spec : options) {
    if (spec.name == option) return &spec;
  }
  return nullptr;
}

std::string or_list(const std::vector<std::string>& words) {
  std::string text;
  for (std::size_t i = 0; i < words.size(); ++i) {
    if (i > 0) text += i + 1 == words.size() ? " or " : ", ";
    text += words[i];
  }
  return text;
}

bool asks_for_help(int argc, char** argv, int first) {
  for (int i = first; i < argc; ++i) {
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) return true;
  }
  return false;
}

namespace {

std::string for_command(const CommandSpec& spec) {
  return spec.name.empty() ? "" : " for " + spec.name;
}

std::vector<std::string> option_names(const CommandSpec& spec) {
  std::vector<std::string> names;
  for (const OptionSpec& option : spec.options) names.push_back(option.name);
  return names;
}

// The options and operands as written, with values attached and kinds respected.
CommandLine read_words(const CommandSpec& spec, int argc, char** argv, int first) {
  CommandLine line;
  line.command = spec.name;
  for (int i = first; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.size() < 2 || word[0] != '-') {
      line.positional.push_back(word);
      continue;
    }
    const OptionSpec* option = spec.find(word);
    if (option == nullptr) {
      for (const auto& [name, where] : spec.elsewhere) {
        if (name == word) {
          throw UsageError(spec.name + " takes no " + word + "; it belongs to " + where);
        }
      }
      throw UsageError("unknown option '" + word + "'" + for_command(spec) +
                       did_you_mean(word, option_names(spec)));
    }
    std::vector<std::string>& values = line.options[word];
    if (option->type == ValueType::kFlag) {
      values.emplace_back();
    } else {
      if (i + 1 >= argc) throw UsageError(word + " needs a value");
      values.push_back(argv[++i]);
    }
    if (!option->repeatable && values.size() > 1) throw UsageError(word + " given twice");
  }
  return line;
}

bool is_whole(double value) { return value == std::floor(value); }

void check_value(const OptionSpec& option, const std::string& text) {
  if (option.type == ValueType::kFlag || option.type == ValueType::kText) return;
  if (option.type == ValueType::kChoice) {
    if (std::find(option.choices.begin(), option.choices.end(), text) != option.choices.end()) {
      return;
    }
    throw UsageError(option.name + " must be " + or_list(option.choices) + ", not '" + text + "'" +
                     did_you_mean(text, option.choices));
  }
  const double value = parse_number(text, option.name);
  const auto refuse = [&](const std::string& what) {
    throw UsageError(option.name + " must be " + what + ", not '" + text + "'");
  };
  switch (option.type) {
    case ValueType::kPositive:
      if (!(value > 0)) refuse("positive");
      break;
    case ValueType::kNonNegative:
      if (!(value >= 0)) refuse("zero or positive");
      break;
    case ValueType::kCount:
      if (!(value >= 1) || !is_whole(value) || value > 2e9) {
        refuse("a whole number of at least 1");
      }
      break;
    case ValueType::kWhole:
      if (!(value >= 0) || !is_whole(value) || value > 9e15) refuse("a whole number >= 0");
      break;
    default:
      break;
  }
}

// "the closed-loop methods, --method iv or didim", or "--method ml" when no family is named.
std::string methods_phrase(const CommandSpec& spec, const std::vector<std::string>& methods) {
  const std::string listed = spec.selector + " " + or_list(methods);
  for (const MethodFamily& family : spec.families) {
    if (family.methods == methods) return family.name + ", " + listed;
  }
  return listed;
}

void check_methods(const CommandSpec& spec, const CommandLine& line) {
  if (spec.selector.empty() || !line.has(spec.selector)) return;
  const std::string& method = line.one(spec.selector);
  for (const auto& [name, values] : line.options) {
    const OptionSpec& option = *spec.find(name);
    if (option.methods.empty()) continue;
    if (std::find(option.methods.begin(), option.methods.end(), method) != option.methods.end()) {
      continue;
    }
    throw UsageError(name + " belongs to " + methods_phrase(spec, option.methods) + ", not " +
                     spec.selector + " " + method);
  }
}

void check_needs_and_exclusions(const CommandSpec& spec, const CommandLine& line) {
  for (const auto& [name, values] : line.options) {
    const OptionSpec& option = *spec.find(name);
    if (!option.needs.empty() && !line.has(option.needs)) {
      throw UsageError(name + " belongs to " + option.needs + "; add " + option.needs);
    }
  }
  for (const Exclusion& pair : spec.exclusive) {
    if (line.has(pair.first) && line.has(pair.second)) {
      throw UsageError(pair.first + " and " + pair.second + " exclude each other" +
                       (pair.reason.empty() ? "" : " (" + pair.reason + ")"));
    }
  }
}

void check_operands_and_required(const CommandSpec& spec, const CommandLine& line) {
  if (spec.operands.empty() && !line.positional.empty()) {
    const std::string& word = line.positional.front();
    throw UsageError(
        "unexpected argument '" + word + "'" + for_command(spec) +
        (spec.find("--data") != nullptr ? " (each data file needs its own --data)" : ""));
  }
  for (const OptionSpec& option : spec.options) {
    if (option.required && !line.has(option.name)) {
      throw UsageError((spec.name.empty() ? std::string("missing ") : spec.name + " needs ") +
                       option.name + (option.value.empty() ? "" : " " + option.value));
    }
  }
}

}  // namespace

CommandLine parse_command(const CommandSpec& spec, int argc, char** argv, int first) {
  CommandLine line = read_words(spec, argc, argv, first);
  for (const auto& [name, values] : line.options) {
    for (const std::string& value : values) check_value(*spec.find(name), value);
  }
  check_methods(spec, line);
  check_needs_and_exclusions(spec, line);
  check_operands_and_required(spec, line);
  return line;
}

}  // namespace modelgen
