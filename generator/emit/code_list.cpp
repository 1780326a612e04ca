// Quoted names and number literals in lists.

#include "generator/emit/code_list.hpp"

namespace modelgen::gen {

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      static const char kHex[] = "0123456789abcdef";
      out += "\\u00";
      out += kHex[(c >> 4) & 15];
      out += kHex[c & 15];
    } else {
      out += c;
    }
  }
  return out + "\"";
}

void write_list(const std::vector<std::string>& items, CodeWriter& out) {
  std::string line;
  for (const std::string& text : items) {
    const std::string item = text + ",";
    if (!line.empty() && line.size() + 1 + item.size() > 92) {
      out.line(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + item;
  }
  if (!line.empty()) out.line(line);
}

void write_name_list(const std::vector<std::string>& names, CodeWriter& out) {
  std::vector<std::string> items;
  for (const std::string& name : names) items.push_back(quoted(name));
  write_list(items, out);
}

void write_number_list(const std::vector<double>& values, Scalar scalar, CodeWriter& out) {
  std::vector<std::string> items;
  for (double value : values) items.push_back(format_literal(value, scalar));
  write_list(items, out);
}

}  // namespace modelgen::gen
