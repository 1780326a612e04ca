// The help and usage text of a command, rendered from its option table
// (modelgen/model/option_table.hpp), so that what --help says is what the parser accepts.

#include <sstream>

#include "modelgen/model/option_table.hpp"

namespace modelgen {

namespace {

constexpr std::size_t kHelpWidth = 96;
constexpr std::size_t kHelpIndent = 26;

std::string program_and_command(const CommandSpec& spec) {
  return spec.name.empty() ? spec.program : spec.program + " " + spec.name;
}

std::string option_with_value(const OptionSpec& option) {
  if (option.type == ValueType::kFlag) return option.name;
  std::string choices;
  for (const std::string& choice : option.choices) choices += (choices.empty() ? "" : "|") + choice;
  const std::string value = !option.value.empty() ? option.value : !choices.empty() ? choices : "X";
  return option.name + " " + value + (option.repeatable ? "..." : "");
}

// The sentence after an option's help: unit, default, allowed values, methods, what it needs.
std::string option_facts(const CommandSpec& spec, const OptionSpec& option) {
  std::vector<std::string> facts;
  if (!option.unit.empty()) facts.push_back("unit " + option.unit);
  if (!option.default_value.empty()) facts.push_back("default " + option.default_value);
  if (option.type == ValueType::kChoice && !option.value.empty()) {
    facts.push_back("one of " + or_list(option.choices));
  }
  if (option.repeatable) facts.push_back("may be repeated");
  if (option.required) facts.push_back("required");
  if (!option.methods.empty()) {
    facts.push_back("with " + spec.selector + " " + or_list(option.methods) + " only");
  }
  if (!option.needs.empty()) facts.push_back("with " + option.needs + " only");
  std::string text;
  for (const std::string& fact : facts) text += (text.empty() ? "(" : "; ") + fact;
  return text.empty() ? text : text + ")";
}

// One paragraph wrapped at kHelpWidth, every line after the first indented by `indent`.
std::string wrap_paragraph(const std::string& text, std::size_t first_column, std::size_t indent) {
  std::istringstream words(text);
  std::string out;
  std::size_t column = first_column;
  bool first_word = true;
  for (std::string word; words >> word; first_word = false) {
    if (!first_word && column + 1 + word.size() > kHelpWidth) {
      out += "\n" + std::string(indent, ' ');
      column = indent;
    } else if (!first_word) {
      out += ' ';
      ++column;
    }
    out += word;
    column += word.size();
  }
  return out;
}

// `text` wrapped at kHelpWidth: each of its lines a paragraph, every output line after the
// first indented by `indent`.
std::string wrap(const std::string& text, std::size_t first_column, std::size_t indent) {
  std::string out;
  std::istringstream lines(text);
  std::size_t column = first_column;
  for (std::string line; std::getline(lines, line); column = indent) {
    if (!out.empty()) out += "\n" + std::string(indent, ' ');
    out += wrap_paragraph(line, column, indent);
  }
  return out;
}

void write_option(std::ostream& out, const CommandSpec& spec, const OptionSpec& option) {
  const std::string head = "  " + option_with_value(option);
  std::string line = head;
  if (head.size() + 2 > kHelpIndent) {
    out << head << "\n";
    line = std::string(kHelpIndent, ' ');
  } else {
    line += std::string(kHelpIndent - head.size(), ' ');
  }
  const std::string facts = option_facts(spec, option);
  out << line << wrap(option.help + (facts.empty() ? "" : " " + facts), kHelpIndent, kHelpIndent)
      << "\n";
}

std::vector<std::string> groups_in_order(const CommandSpec& spec) {
  std::vector<std::string> groups;
  for (const OptionSpec& option : spec.options) {
    bool seen = false;
    for (const std::string& group : groups) seen = seen || group == option.group;
    if (!seen) groups.push_back(option.group);
  }
  return groups;
}

}  // namespace

std::string wrapped(const std::string& text, std::size_t column, std::size_t indent) {
  return wrap(text, column, indent);
}

std::string usage_line(const CommandSpec& spec) {
  std::string line = program_and_command(spec);
  if (!spec.operands.empty()) line += " " + spec.operands;
  bool optional = false;
  for (const OptionSpec& option : spec.options) {
    if (option.required) {
      line += " " + option_with_value(option);
    } else {
      optional = true;
    }
  }
  return optional ? line + " [OPTIONS]" : line;
}

std::string command_help(const CommandSpec& spec) {
  std::ostringstream out;
  out << "usage: " << usage_line(spec) << "\n\n" << wrap(spec.summary, 0, 0) << "\n";
  for (const std::string& group : groups_in_order(spec)) {
    out << "\n" << (group.empty() ? std::string("Options") : group) << ":\n";
    for (const OptionSpec& option : spec.options) {
      if (option.group == group) write_option(out, spec, option);
    }
  }
  if (!spec.details.empty())
    out << "\n" << spec.details << (spec.details.back() == '\n' ? "" : "\n");
  return out.str();
}

}  // namespace modelgen
