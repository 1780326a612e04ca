// Prototypes: documentation from templates, parameter lists from the registry, line breaking.

#include "generator/emit/prototype.hpp"

#include "generator/emit/printer.hpp"

namespace modelgen::gen {

namespace {

// Prototypes, declared with ';' and defined with ' {', stay within 100 columns either way.
constexpr std::size_t kPrototypeWidth = 98;

std::string documentation(const EmittedFunction& function) {
  std::string text =
      function.sincos
          ? Printer(embedded_template("sincos_variant")).set("function", function.entry->name).render()
          : Printer(embedded_template(std::string("functions/") + function.entry->name)).render();
  for (const UnwrittenEntries& entries : function.unwritten) {
    text += Printer(embedded_template("unwritten_entries"))
                .set("array", entries.array)
                .set("written", static_cast<long long>(entries.total - entries.indices.size()))
                .set("total", static_cast<long long>(entries.total))
                .render();
  }
  return text;
}

}  // namespace

std::string function_prototype(const EmittedFunction& function, Scalar scalar, bool documented) {
  const std::string text = without_final_newline(
      Printer(embedded_template("prototype"))
          .set_block("documentation",
                     [&](CodeWriter& out) {
                       if (documented) out.lines_of(documentation(function));
                     })
          .set("function", function.name)
          .set("parameters", parameter_list(function.inputs, function.outputs, scalar))
          .render());
  const std::size_t last_line = text.rfind('\n') + 1;  // 0 when there is no documentation
  return text.substr(0, last_line) + wrap_parameters(text.substr(last_line), kPrototypeWidth);
}

std::string parameter_list(const std::vector<std::string>& inputs,
                           const std::vector<std::string>& outputs, Scalar scalar) {
  std::string list;
  auto add = [&](const char* template_name, const std::string& name) {
    list +=
        (list.empty() ? "" : ", ") + without_final_newline(Printer(embedded_template(template_name))
                                                               .set("scalar", scalar_name(scalar))
                                                               .set("name", name)
                                                               .render());
  };
  for (const std::string& name : inputs) add("parameter_input", name);
  for (const std::string& name : outputs) add("parameter_output", name);
  return list;
}

std::string wrap_parameters(const std::string& line, std::size_t width) {
  const std::size_t open = line.find('('), close = line.rfind(')');
  if (line.size() <= width || open == std::string::npos || close == std::string::npos) {
    return line;
  }
  // The items: each parameter with its comma, the last one with the rest of the line.
  const std::string list = line.substr(open + 1, close - open - 1);
  std::vector<std::string> items;
  for (std::size_t start = 0;;) {
    const std::size_t comma = list.find(", ", start);
    if (comma == std::string::npos) {
      items.push_back(list.substr(start) + line.substr(close));
      break;
    }
    items.push_back(list.substr(start, comma - start) + ",");
    start = comma + 2;
  }
  std::string text = line.substr(0, open + 1) + items.front();
  std::size_t line_start = 0;
  for (std::size_t i = 1; i < items.size(); ++i) {
    if (text.size() - line_start + 1 + items[i].size() > width) {
      line_start = text.size() + 1;
      text += "\n" + std::string(open + 1, ' ') + items[i];
    } else {
      text += " " + items[i];
    }
  }
  return text;
}

}  // namespace modelgen::gen
