// The banner and its operation-count table, columns padded to line up.

#include "generator/emit/banner.hpp"

#include <algorithm>

#include "generator/emit/printer.hpp"
#include "generator/version.hpp"

namespace modelgen::gen {

namespace {

std::string pad_left(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : std::string(width - text.size(), ' ') + text;
}

std::string pad_right(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : text + std::string(width - text.size(), ' ');
}

void write_op_table(std::span<const EmittedFunction> functions, CodeWriter& out) {
  // The name column fits the longest function name.
  std::size_t name_width = 34;
  for (const EmittedFunction& f : functions) name_width = std::max(name_width, f.name.size() + 2);
  auto row = [&](const std::string& name, const std::string& mul, const std::string& add,
                 const std::string& trig) {
    out.line(without_final_newline(Printer(embedded_template("banner_row"))
                                       .set("function", pad_right(name, name_width))
                                       .set("mul", pad_left(mul, 7))
                                       .set("add", pad_left(add, 7))
                                       .set("trig", pad_left(trig, 9))
                                       .render()));
  };
  row("Function", "mul", "add", "sin/cos");
  for (const EmittedFunction& f : functions) {
    row(f.name, std::to_string(f.counts.mul), std::to_string(f.counts.add),
        std::to_string(f.counts.trig));
  }
}

}  // namespace

std::string render_banner(const std::string& file, const RenderInput& in,
                          std::span<const EmittedFunction> functions) {
  return without_final_newline(
      Printer(embedded_template("banner"))
          .set("file", file)
          .set("version", kVersion)
          .set("input", in.input.input_name)
          .set("command", in.input.command_line)
          .set("sha256", in.sha256)
          .set_block("identified",
                     [&](CodeWriter& out) {
                       if (!in.input.estimate) return;
                       const EstimateFile& estimate = *in.input.estimate;
                       out.lines_of(Printer(embedded_template("banner_identified"))
                                        .set("file", estimate.file_name)
                                        .set("method", estimate.method.empty()
                                                           ? ""
                                                           : ", method " + estimate.method)
                                        .set("sha256", estimate.sha256)
                                        .render());
                     })
          .set_block("op_table", [&](CodeWriter& out) { write_op_table(functions, out); })
          .render());
}

}  // namespace modelgen::gen
