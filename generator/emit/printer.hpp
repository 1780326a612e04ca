// Fills a Template with named values and blocks of lines. A missing value or a value no
// placeholder uses is a generator bug and raises std::logic_error with the template position.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "generator/emit/template.hpp"

namespace modelgen::gen {

/// Lines of generated text for a block placeholder.
class CodeWriter {
 public:
  void line(std::string_view text) { lines_.emplace_back(text); }
  void blank() { lines_.emplace_back(); }
  /// Each line of `text` (a final newline ends the last line, it does not start another).
  void lines_of(std::string_view text);
  const std::vector<std::string>& lines() const { return lines_; }

 private:
  std::vector<std::string> lines_;
};

/// `text` without its final newline, if it has one (a rendered template used as a value).
std::string without_final_newline(std::string text);

class Printer {
 public:
  explicit Printer(const Template& tmpl) : template_(tmpl) {}

  Printer& set(std::string_view name, std::string_view value);
  Printer& set(std::string_view name, long long value);
  Printer& set_block(std::string_view name, const std::function<void(CodeWriter&)>& fill);

  /// The filled template, every line ending in '\n'.
  std::string render() const;

 private:
  const Template& template_;
  std::map<std::string, std::string, std::less<>> values_;
  std::map<std::string, std::vector<std::string>, std::less<>> blocks_;
};

}  // namespace modelgen::gen
