// A parsed text template (templates/*.tmpl): literal text and $name$ placeholders with their
// positions, so the printer can report a missing or unused value at templates/x.tmpl:line:col.
// Syntax: $name$ is a placeholder, $$ a literal dollar sign, a line starting with $# a comment.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace modelgen::gen {

struct TemplatePiece {
  bool is_placeholder = false;
  std::string text;  ///< literal text, or the placeholder's name
  int line = 0;      ///< 1-based position in the template file
  int column = 0;
};

struct TemplateLine {
  std::vector<TemplatePiece> pieces;
  /// The line is exactly one placeholder with only spaces before it: it takes a block.
  bool is_block = false;
  int indent = 0;
};

class Template {
 public:
  /// Parses `text`; `name` (e.g. "templates/model.hpp.tmpl") is used in error positions.
  /// Throws std::logic_error on a malformed placeholder (an unpaired $).
  Template(std::string name, std::string_view text);

  const std::string& name() const { return name_; }
  const std::vector<TemplateLine>& lines() const { return lines_; }

 private:
  std::string name_;
  std::vector<TemplateLine> lines_;
};

/// The templates compiled into modelgen (embed-templates.cmake); `get("model.hpp")` returns
/// templates/model.hpp.tmpl. Throws std::logic_error for an unknown name.
const Template& embedded_template(std::string_view name);

}  // namespace modelgen::gen
