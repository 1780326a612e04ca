// Fills the model templates: derives each function symbolically, writes its statements for
// double and float, and assembles banner, header, source and manifest.

#include "generator/emit/model_emitter.hpp"

#include <cctype>

#include "generator/dynamics/newton_euler.hpp"
#include "generator/emit/printer.hpp"
#include "generator/output/sha256.hpp"
#include "generator/version.hpp"

namespace modelgen::gen {

namespace {

struct FunctionSpec {
  std::string name;  // also the name of its signature template in templates/functions/
  std::vector<FunctionOutput> outputs;
  std::vector<std::string> parameters;  // the input arrays, for unused-parameter checks
};

struct EmittedFunction {
  const FunctionSpec* spec;
  std::vector<FunctionBody> body;  // one per GenerationInput::scalars entry
};

std::string signature(const std::string& name, Scalar scalar) {
  std::string text =
      Printer(embedded_template("functions/" + name)).set("scalar", scalar_name(scalar)).render();
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

// The prototype without its leading documentation comment (for the float overload, which
// shares the double one's documentation).
std::string undocumented(const std::string& text) {
  std::size_t start = 0;
  while (text.compare(start, 2, "//") == 0) start = text.find('\n', start) + 1;
  return text.substr(start);
}

std::string json_string(const std::string& text) {
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

std::string pad_left(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : std::string(width - text.size(), ' ') + text;
}

std::string pad_right(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : text + std::string(width - text.size(), ' ');
}

bool uses_array(const FunctionBody& body, const std::string& array) {
  // A body uses an input array when some statement reads array[...].
  const std::string needle = array + "[";
  for (const std::string& line : body.lines) {
    for (std::size_t at = line.find(needle); at != std::string::npos; at = line.find(needle, at + 1)) {
      if (at == 0 || !(std::isalnum(static_cast<unsigned char>(line[at - 1])) || line[at - 1] == '_')) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace

GeneratedModel emit_model(const RobotModel& model, const GenerationInput& input) {
  const RigidBodyTree& tree = model.tree;
  const int dof = tree.dof;
  const int num_params = static_cast<int>(tree.params.size());

  ExprGraph graph;
  const SymbolicInputs symbols = make_symbolic_inputs(graph, tree);
  std::vector<FunctionSpec> specs;
  {
    const std::vector<ExprId> W = derive_standard_regressor(graph, tree, symbols);
    FunctionSpec spec{"idim_regressor_standard", {}, {"q", "dq", "ddq"}};
    for (int i = 0; i < dof; ++i) {
      for (int k = 0; k < num_params; ++k) {
        const int index = i * num_params + k;
        spec.outputs.push_back({"W[" + std::to_string(index) + "]", W[index],
                                i == 0 ? tree.params[k].name : std::string()});
      }
    }
    specs.push_back(std::move(spec));
  }
  {
    const std::vector<ExprId> tau = derive_inverse_dynamics(graph, tree, symbols);
    FunctionSpec spec{"inverse_dynamics_standard", {}, {"q", "dq", "ddq", "p"}};
    for (int i = 0; i < dof; ++i) {
      spec.outputs.push_back({"tau[" + std::to_string(i) + "]", tau[i], ""});
    }
    specs.push_back(std::move(spec));
  }

  std::vector<EmittedFunction> functions;
  GeneratedModel result;
  for (const FunctionSpec& spec : specs) {
    EmittedFunction f{&spec, {}};
    for (Scalar scalar : input.scalars) {
      f.body.push_back(write_statements(graph, spec.outputs, scalar));
    }
    result.functions.push_back({spec.name, f.body[0].counts});
    functions.push_back(std::move(f));
  }

  const std::string sha256 = sha256_hex(input.input_bytes);
  auto banner = [&](const std::string& file) {
    return Printer(embedded_template("banner"))
        .set("file", file)
        .set("version", kVersion)
        .set("input", input.input_name)
        .set("command", input.command_line)
        .set("sha256", sha256)
        .set_block("op_table",
                   [&](CodeWriter& out) {
                     auto row = [&](const std::string& name, const std::string& mul,
                                    const std::string& add, const std::string& trig) {
                       std::string text = Printer(embedded_template("banner_row"))
                                              .set("function", pad_right(name, 30))
                                              .set("mul", pad_left(mul, 7))
                                              .set("add", pad_left(add, 7))
                                              .set("trig", pad_left(trig, 9))
                                              .render();
                       text.pop_back();
                       out.line(text);
                     };
                     row("Function", "mul", "add", "sin/cos");
                     for (const FunctionReport& f : result.functions) {
                       row(f.name, std::to_string(f.counts.mul), std::to_string(f.counts.add),
                           std::to_string(f.counts.trig));
                     }
                   })
        .render();
  };
  auto strip_newline = [](std::string text) {
    if (!text.empty() && text.back() == '\n') text.pop_back();
    return text;
  };

  std::string guard = "MODELGEN_";
  for (char c : model.name) guard += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  guard += "_HPP_";

  const std::string header_name = input.stem + ".hpp";
  const std::string source_name = input.stem + ".cpp";
  const std::string header =
      Printer(embedded_template("model.hpp"))
          .set("banner", strip_newline(banner(header_name)))
          .set("include_guard", guard)
          .set("robot", model.name)
          .set("format_version", kFormatVersion)
          .set("dof", dof)
          .set("standard_param_count", num_params)
          .set_block("declarations",
                     [&](CodeWriter& out) {
                       for (std::size_t i = 0; i < functions.size(); ++i) {
                         if (i > 0) out.blank();
                         const std::string& name = functions[i].spec->name;
                         for (std::size_t s = 0; s < input.scalars.size(); ++s) {
                           std::string text = signature(name, input.scalars[s]);
                           if (s > 0) text = undocumented(text);  // documented once
                           const std::string declaration =
                               strip_newline(Printer(embedded_template("function_declaration"))
                                                 .set("signature", text)
                                                 .render());
                           std::size_t start = 0;
                           while (start < declaration.size()) {
                             std::size_t end = declaration.find('\n', start);
                             if (end == std::string::npos) end = declaration.size();
                             out.line(declaration.substr(start, end - start));
                             start = end + 1;
                           }
                         }
                       }
                     })
          .render();

  const std::string source =
      Printer(embedded_template("model.cpp"))
          .set("banner", strip_newline(banner(source_name)))
          .set("header", header_name)
          .set("robot", model.name)
          .set_block("standard_param_names",
                     [&](CodeWriter& out) {
                       std::string line;
                       for (int k = 0; k < num_params; ++k) {
                         const std::string item = json_string(tree.params[k].name) + ",";
                         if (!line.empty() && line.size() + 1 + item.size() > 92) {
                           out.line(line);
                           line.clear();
                         }
                         line += (line.empty() ? "" : " ") + item;
                       }
                       if (!line.empty()) out.line(line);
                     })
          .set_block("definitions",
                     [&](CodeWriter& out) {
                       bool first = true;
                       for (const EmittedFunction& f : functions) {
                         for (std::size_t s = 0; s < input.scalars.size(); ++s) {
                           const Scalar scalar = input.scalars[s];
                           if (!first) out.blank();
                           first = false;
                           const FunctionBody& body = f.body[s];
                           const std::string definition =
                               Printer(embedded_template("function_definition"))
                                   .set("signature", signature(f.spec->name, scalar))
                                   .set_block("unused",
                                              [&](CodeWriter& unused) {
                                                for (const std::string& array : f.spec->parameters) {
                                                  if (uses_array(body, array)) continue;
                                                  unused.line(strip_newline(
                                                      Printer(embedded_template("unused_parameter"))
                                                          .set("parameter", array)
                                                          .render()));
                                                }
                                              })
                                   .set_block("body",
                                              [&](CodeWriter& lines) {
                                                for (const std::string& l : body.lines) lines.line(l);
                                              })
                                   .render();
                           std::size_t start = 0;
                           const std::string text = strip_newline(definition);
                           while (start <= text.size()) {
                             std::size_t end = text.find('\n', start);
                             if (end == std::string::npos) end = text.size();
                             out.line(text.substr(start, end - start));
                             start = end + 1;
                           }
                         }
                       }
                     })
          .render();

  const std::string manifest =
      Printer(embedded_template("manifest.json"))
          .set("version", kVersion)
          .set("format_version", kFormatVersion)
          .set("robot", model.name)
          .set("input", json_string(input.input_name))
          .set("sha256", sha256)
          .set("command", json_string(input.command_line))
          .set("dof", dof)
          .set_block("standard_parameters",
                     [&](CodeWriter& out) {
                       for (int k = 0; k < num_params; ++k) {
                         out.line(json_string(tree.params[k].name) + (k + 1 < num_params ? "," : ""));
                       }
                     })
          .set_block("functions",
                     [&](CodeWriter& out) {
                       for (std::size_t i = 0; i < result.functions.size(); ++i) {
                         const FunctionReport& f = result.functions[i];
                         out.line("{\"name\": " + json_string(f.name) +
                                  ", \"mul\": " + std::to_string(f.counts.mul) +
                                  ", \"add\": " + std::to_string(f.counts.add) +
                                  ", \"sin_cos\": " + std::to_string(f.counts.trig) + "}" +
                                  (i + 1 < result.functions.size() ? "," : ""));
                       }
                     })
          .render();

  result.files.add(header_name, header);
  result.files.add(source_name, source);
  result.files.add(input.stem + ".json", manifest);
  return result;
}

}  // namespace modelgen::gen
