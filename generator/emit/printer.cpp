// Template filling: block placeholders indent every line of their block to the placeholder's
// column and vanish when the block is empty; inline placeholders take their value verbatim.

#include "generator/emit/printer.hpp"

#include <set>
#include <stdexcept>

namespace modelgen::gen {

void CodeWriter::lines_of(std::string_view text) {
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    lines_.emplace_back(text.substr(start, end - start));
    start = end + 1;
  }
}

std::string without_final_newline(std::string text) {
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

Printer& Printer::set(std::string_view name, std::string_view value) {
  values_[std::string(name)] = std::string(value);
  return *this;
}

Printer& Printer::set(std::string_view name, long long value) {
  return set(name, std::to_string(value));
}

Printer& Printer::set_block(std::string_view name, const std::function<void(CodeWriter&)>& fill) {
  CodeWriter writer;
  fill(writer);
  blocks_[std::string(name)] = writer.lines();
  return *this;
}

std::string Printer::render() const {
  std::set<std::string, std::less<>> used;
  std::string out;
  auto position = [&](const TemplatePiece& piece) {
    return template_.name() + ":" + std::to_string(piece.line) + ":" + std::to_string(piece.column);
  };
  for (const TemplateLine& line : template_.lines()) {
    if (line.is_block) {
      const TemplatePiece& piece = line.pieces[0];
      const std::string indent(line.indent, ' ');
      std::vector<std::string> block;
      if (auto b = blocks_.find(piece.text); b != blocks_.end()) {
        block = b->second;
      } else if (auto v = values_.find(piece.text); v != values_.end()) {
        std::size_t start = 0;
        const std::string& text = v->second;
        while (start <= text.size()) {
          std::size_t end = text.find('\n', start);
          if (end == std::string::npos) end = text.size();
          block.push_back(text.substr(start, end - start));
          start = end + 1;
        }
      } else {
        throw std::logic_error(position(piece) + ": no value for placeholder '" + piece.text + "'");
      }
      used.insert(piece.text);
      for (const std::string& text : block) out += (text.empty() ? "" : indent) + text + "\n";
      continue;
    }
    for (const TemplatePiece& piece : line.pieces) {
      if (!piece.is_placeholder) {
        out += piece.text;
        continue;
      }
      auto v = values_.find(piece.text);
      if (v == values_.end()) {
        throw std::logic_error(position(piece) + ": no value for placeholder '" + piece.text + "'" +
                               (blocks_.count(piece.text) ? " (a block needs its own line)" : ""));
      }
      used.insert(piece.text);
      out += v->second;
    }
    out += "\n";
  }
  for (const auto& [name, value] : values_) {
    if (!used.count(name)) {
      throw std::logic_error(template_.name() + ": value '" + name + "' is used by no placeholder");
    }
  }
  for (const auto& [name, block] : blocks_) {
    if (!used.count(name)) {
      throw std::logic_error(template_.name() + ": block '" + name + "' is used by no placeholder");
    }
  }
  return out;
}

}  // namespace modelgen::gen
