// Template parsing and the registry of templates embedded at build time.

#include "generator/emit/template.hpp"

#include <map>
#include <memory>
#include <stdexcept>

namespace modelgen::gen {

// Defined in the source that embed-templates.cmake writes into the build tree.
struct EmbeddedTemplate {
  const char* name;
  const char* text;
};
extern const EmbeddedTemplate kEmbeddedTemplates[];
extern const int kEmbeddedTemplateCount;

Template::Template(std::string name, std::string_view text) : name_(std::move(name)) {
  int line_number = 0;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    ++line_number;
    const bool last = end == text.size();
    start = end + 1;
    if (last && line.empty()) break;  // the file's final newline ends the last line
    if (line.substr(0, 2) == "$#") continue;

    TemplateLine parsed;
    std::string literal;
    std::size_t i = 0;
    while (i < line.size()) {
      if (line[i] != '$') {
        literal += line[i++];
        continue;
      }
      if (i + 1 < line.size() && line[i + 1] == '$') {
        literal += '$';
        i += 2;
        continue;
      }
      const std::size_t close = line.find('$', i + 1);
      if (close == std::string_view::npos) {
        throw std::logic_error(name_ + ":" + std::to_string(line_number) + ":" +
                               std::to_string(i + 1) + ": unpaired '$' in template");
      }
      if (!literal.empty()) parsed.pieces.push_back({false, literal, line_number, 0});
      literal.clear();
      parsed.pieces.push_back({true, std::string(line.substr(i + 1, close - i - 1)), line_number,
                               static_cast<int>(i + 1)});
      i = close + 1;
    }
    if (!literal.empty()) parsed.pieces.push_back({false, literal, line_number, 0});
    if (parsed.pieces.size() == 2 && parsed.pieces[1].is_placeholder &&
        parsed.pieces[0].text.find_first_not_of(' ') == std::string::npos) {
      parsed.is_block = true;
      parsed.indent = static_cast<int>(parsed.pieces[0].text.size());
      parsed.pieces.erase(parsed.pieces.begin());
    } else if (parsed.pieces.size() == 1 && parsed.pieces[0].is_placeholder) {
      parsed.is_block = true;
    }
    lines_.push_back(std::move(parsed));
  }
}

const Template& embedded_template(std::string_view name) {
  static const auto* const kParsed = [] {
    auto* parsed = new std::map<std::string, Template, std::less<>>();
    for (int i = 0; i < kEmbeddedTemplateCount; ++i) {
      const std::string key = kEmbeddedTemplates[i].name;
      parsed->emplace(key, Template("templates/" + key + ".tmpl", kEmbeddedTemplates[i].text));
    }
    return parsed;
  }();
  auto found = kParsed->find(name);
  if (found == kParsed->end()) {
    throw std::logic_error("no embedded template '" + std::string(name) + "'");
  }
  return found->second;
}

}  // namespace modelgen::gen
