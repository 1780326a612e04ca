// Comma-separated lists in generated sources (parameter names, number literals), wrapped to
// the 100-column generated style.
#pragma once

#include <string>
#include <vector>

#include "generator/emit/number_format.hpp"
#include "generator/emit/printer.hpp"

namespace modelgen::gen {

/// `text` as a double-quoted C string literal (also valid JSON): '"' and '\' escaped, control
/// characters as \u00XX.
std::string quoted(const std::string& text);

/// Items, each followed by a comma, several per line, lines kept under 92 columns.
void write_list(const std::vector<std::string>& items, CodeWriter& out);

/// Quoted names, as write_list.
void write_name_list(const std::vector<std::string>& names, CodeWriter& out);

/// Number literals of `scalar`, as write_list.
void write_number_list(const std::vector<double>& values, Scalar scalar, CodeWriter& out);

}  // namespace modelgen::gen
