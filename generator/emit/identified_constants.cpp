// Declarations and definitions of the identified base-parameter arrays (--params).

#include "generator/emit/identified_constants.hpp"

#include "generator/emit/render_input.hpp"

namespace modelgen::gen {

std::string identified_base_array(Scalar scalar, const std::vector<Scalar>& scalars) {
  const bool first = !scalars.empty() && scalars.front() == scalar;
  return first ? "kIdentifiedBase" : "kIdentifiedBaseFloat";
}

void write_identified_declarations(const RenderInput& in, CodeWriter& out) {
  if (!in.input.estimate) return;
  for (std::size_t s = 0; s < in.input.scalars.size(); ++s) {
    const Scalar scalar = in.input.scalars[s];
    out.lines_of(Printer(embedded_template(s == 0 ? "identified_base_declaration"
                                                  : "identified_base_rounded_declaration"))
                     .set("scalar", scalar_name(scalar))
                     .set("array", identified_base_array(scalar, in.input.scalars))
                     .render());
  }
}

void write_identified_definitions(const RenderInput& in, CodeWriter& out) {
  if (!in.input.estimate) return;
  for (const Scalar scalar : in.input.scalars) {
    out.lines_of(
        Printer(embedded_template("identified_base_definition"))
            .set("scalar", scalar_name(scalar))
            .set("array", identified_base_array(scalar, in.input.scalars))
            .set_block("values",
                       [&](CodeWriter& values) {
                         for (std::size_t b = 0; b < in.identified_base.size(); ++b) {
                           values.line(without_final_newline(
                               Printer(embedded_template("identified_base_value"))
                                   .set("value", format_literal(in.identified_base[b], scalar))
                                   .set("name", in.base.params[b].name)
                                   .render()));
                         }
                       })
            .render());
  }
}

}  // namespace modelgen::gen
