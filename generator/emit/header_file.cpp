// The header: declarations in file order (each scalar type after the first shares the first
// one's documentation), and the Model struct forwarding to the double entry points the
// registry marks, in registry order.

#include "generator/emit/header_file.hpp"

#include <cctype>

#include "generator/emit/banner.hpp"
#include "generator/emit/identified_constants.hpp"
#include "generator/emit/printer.hpp"
#include "generator/emit/prototype.hpp"
#include "generator/functions/registry.hpp"
#include "modelgen/model/generated_format.hpp"

namespace modelgen::gen {

namespace {

// Wrapped so that, indented in the struct, a member's first lines stay within 100 columns.
constexpr std::size_t kStructMemberWidth = 98;

std::string include_guard(const std::string& robot) {
  std::string guard = "MODELGEN_";
  for (char c : robot) guard += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return guard + "_HPP_";
}

std::vector<std::string> names(const std::vector<ArraySpec>& arrays) {
  std::vector<std::string> out;
  for (const ArraySpec& array : arrays) out.push_back(array.name);
  return out;
}

// `sincos`: the entry's _sincos variant, sin_q and cos_q after q.
std::string model_struct_member(const FunctionEntry& entry, const std::string& robot,
                                bool sincos = false) {
  std::vector<std::string> inputs = names(entry.inputs);
  const std::vector<std::string> outputs = names(entry.outputs);
  if (sincos) inputs.insert(inputs.begin() + 1, {"sin_q", "cos_q"});
  std::string arguments;
  for (const std::vector<std::string>* list : {static_cast<const std::vector<std::string>*>(&inputs), &outputs}) {
    for (const std::string& name : *list) arguments += (arguments.empty() ? "" : ", ") + name;
  }
  const std::string text = Printer(embedded_template("model_struct_member"))
                               .set("function", std::string(entry.name) + (sincos ? "_sincos" : ""))
                               .set("robot", robot)
                               .set("parameters", parameter_list(inputs, outputs, Scalar::kDouble))
                               .set("arguments", arguments)
                               .render();
  const std::size_t first_line_end = text.find('\n');
  return wrap_parameters(text.substr(0, first_line_end), kStructMemberWidth) +
         text.substr(first_line_end);
}

bool emitted(const RenderInput& in, const char* name) {
  for (const EmittedFunction& f : in.functions) {
    if (f.name == name) return true;
  }
  return false;
}

void write_model_struct(const RenderInput& in, CodeWriter& out) {
  // Generic code runs in double: the struct exists when double entry points come first, and
  // only with all its members (a --functions selection without them is for a controller).
  if (in.input.scalars.empty() || in.input.scalars.front() != Scalar::kDouble) return;
  for (const FunctionEntry& entry : function_registry()) {
    if (entry.in_model_struct == InModelStruct::kNo) continue;
    if (!emitted(in, entry.name)) return;
    if (entry.variants == Variants::kSincos && !emitted(in, (std::string(entry.name) + "_sincos").c_str())) {
      return;
    }
  }
  out.lines_of(Printer(embedded_template("model_struct"))
                   .set("robot", in.model.name)
                   .set("sha256", in.sha256)
                   .set_block("members",
                              [&](CodeWriter& members) {
                                for (const FunctionEntry& entry : function_registry()) {
                                  if (entry.in_model_struct == InModelStruct::kNo) continue;
                                  members.lines_of(model_struct_member(entry, in.model.name));
                                }
                                // The _sincos variants, for a caller that needs several
                                // functions at one q (forward dynamics: M and h).
                                for (const FunctionEntry& entry : function_registry()) {
                                  if (entry.in_model_struct == InModelStruct::kNo ||
                                      entry.variants != Variants::kSincos) {
                                    continue;
                                  }
                                  members.lines_of(model_struct_member(entry, in.model.name, true));
                                }
                              })
                   .render());
}

void write_declarations(const RenderInput& in, CodeWriter& out) {
  for (std::size_t i = 0; i < in.functions.size(); ++i) {
    if (i > 0) out.blank();
    for (std::size_t s = 0; s < in.input.scalars.size(); ++s) {
      out.lines_of(
          Printer(embedded_template("function_declaration"))
              .set("signature", function_prototype(in.functions[i], in.input.scalars[s], s == 0))
              .render());
    }
  }
}

}  // namespace

std::string render_header(const RenderInput& in) {
  return Printer(embedded_template("model.hpp"))
      .set("banner", render_banner(in.header_name(), in))
      .set("include_guard", include_guard(in.model.name))
      .set("robot", in.model.name)
      .set("format_version", kGeneratedFormatVersion)
      // The drive-chain constants take the first scalar type asked for.
      .set("scalar", scalar_name(in.input.scalars.front()))
      .set("dof", in.model.dof())
      .set("standard_param_count", static_cast<long long>(in.model.tree.params.size()))
      .set("base_param_count", static_cast<long long>(in.base.params.size()))
      .set("drive_param_count", static_cast<long long>(in.drive_param_names.size()))
      .set("drive_regressor_entry_count", static_cast<long long>(in.drive_regressor_index.size()))
      .set_block("identified_declarations",
                 [&](CodeWriter& out) { write_identified_declarations(in, out); })
      .set_block("model_struct", [&](CodeWriter& out) { write_model_struct(in, out); })
      .set_block("declarations", [&](CodeWriter& out) { write_declarations(in, out); })
      .render();
}

}  // namespace modelgen::gen
