// Fills the model templates: derives each function symbolically, writes its statements for
// double and float, and assembles banner, header, source and manifest.

#include "generator/emit/model_emitter.hpp"

#include <algorithm>
#include <cctype>
#include <functional>
#include <stdexcept>

#include "modelgen/model/base_parameters.hpp"
#include "generator/dynamics/drive_model.hpp"
#include "generator/dynamics/newton_euler.hpp"
#include "generator/dynamics/power_model.hpp"
#include "generator/emit/printer.hpp"
#include "modelgen/model/sha256.hpp"
#include "generator/symbolic/derivative.hpp"
#include "generator/version.hpp"

namespace modelgen::gen {

namespace {

struct FunctionSpec {
  std::string name;  // also the name of its signature template in templates/functions/
  std::vector<FunctionOutput> outputs;
  std::vector<std::string> parameters;  // the input arrays, for unused-parameter checks
  TrigSource trig = TrigSource::kCompute;
  // Lines before the statements: local arrays filled by calls to other entry points (whose
  // operation counts, `calls`, are added to this function's).
  std::function<std::vector<std::string>(Scalar)> prologue{};
  std::vector<std::string> calls{};
};

std::string render_statement(const char* template_name,
                             const std::vector<std::pair<const char*, std::string>>& values) {
  Printer printer(embedded_template(template_name));
  for (const auto& [name, value] : values) printer.set(name, value);
  std::string text = printer.render();
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

std::string local_array(Scalar scalar, const std::string& name, const std::string& size) {
  return render_statement("statements/local_array",
                          {{"scalar", scalar_name(scalar)}, {"name", name}, {"size", size}});
}

std::string call(const std::string& function, const std::string& arguments) {
  return render_statement("statements/call", {{"function", function}, {"arguments", arguments}});
}

ExprId input_symbol(ExprGraph& graph, const std::string& array, int index) {
  return graph.symbol({array + "[" + std::to_string(index) + "]", SymbolKind::kInput, ""});
}

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

// A JSON number that reads back as the same double ("1.0", "0.05185").
std::string json_number(double value) { return format_literal(value, Scalar::kDouble); }

// Quoted names, comma-terminated, wrapped before 92 columns.
// Items separated by commas, wrapped to fit the 100-column generated style.
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
  std::vector<std::string> quoted;
  for (const std::string& name : names) quoted.push_back(json_string(name));
  write_list(quoted, out);
}

std::vector<double> as_vector(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

void write_number_list(const std::vector<double>& values, Scalar scalar, CodeWriter& out) {
  std::vector<std::string> literals;
  for (double value : values) literals.push_back(format_literal(value, scalar));
  write_list(literals, out);
}

std::string pad_left(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : std::string(width - text.size(), ' ') + text;
}

std::string pad_right(const std::string& text, std::size_t width) {
  return text.size() >= width ? text : text + std::string(width - text.size(), ' ');
}

bool uses_array(const FunctionBody& body, const std::string& array) {
  // A body uses an input array when some statement reads array[...] or passes it to a call
  // ("(q," or " q)"); trailing comments, which may name inputs (the columns of a Jacobian), do
  // not count.
  for (const std::string& full_line : body.lines) {
    const std::string line = full_line.substr(0, full_line.find("//"));
    for (std::size_t at = line.find(array); at != std::string::npos;
         at = line.find(array, at + 1)) {
      const bool inside_name =
          at > 0 && (std::isalnum(static_cast<unsigned char>(line[at - 1])) || line[at - 1] == '_');
      if (inside_name) continue;
      const std::size_t end = at + array.size();
      if (end < line.size() && (line[end] == '[' || line[end] == ',' || line[end] == ')')) {
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

  const BaseParameterSet base = derive_base_parameters(tree);
  const int num_base = static_cast<int>(base.params.size());

  ExprGraph graph;
  const SymbolicInputs symbols = make_symbolic_inputs(graph, tree);
  std::vector<FunctionSpec> specs;
  const std::vector<ExprId> W = derive_standard_regressor(graph, tree, symbols);
  {
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
    // The base regressor is the standard one restricted to the independent columns.
    FunctionSpec spec{"idim_regressor", {}, {"q", "dq", "ddq"}};
    for (int i = 0; i < dof; ++i) {
      for (int b = 0; b < num_base; ++b) {
        spec.outputs.push_back({"W[" + std::to_string(i * num_base + b) + "]",
                                W[i * num_params + base.params[b].standard_index],
                                i == 0 ? base.params[b].name : std::string()});
      }
    }
    specs.push_back(std::move(spec));
  }
  {
    // Newton-Euler with each base parameter in place of the standard one it is built on and
    // the absorbed parameters at zero: tau = W_std p = W_base beta (Gautier & Briot eq. 4).
    SymbolicInputs base_symbols = symbols;
    std::fill(base_symbols.p.begin(), base_symbols.p.end(), graph.zero());
    for (int b = 0; b < num_base; ++b) {
      base_symbols.p[base.params[b].standard_index] =
          graph.symbol({"beta[" + std::to_string(b) + "]", SymbolKind::kInput, ""});
    }
    const std::vector<ExprId> tau = derive_inverse_dynamics(graph, tree, base_symbols);
    FunctionSpec spec{"inverse_dynamics", {}, {"q", "dq", "ddq", "beta"}};
    for (int i = 0; i < dof; ++i) {
      spec.outputs.push_back({"tau[" + std::to_string(i) + "]", tau[i], ""});
    }
    specs.push_back(std::move(spec));

    // d tau / d(q, dq, ddq), the state part of B in Bona & Curatella eq. 15-16, from the same
    // DAG: derivatives of Newton-Euler intermediates stay intermediates. The first row names
    // the state variable of each column.
    std::vector<ExprId> state = symbols.q;
    state.insert(state.end(), symbols.dq.begin(), symbols.dq.end());
    state.insert(state.end(), symbols.ddq.begin(), symbols.ddq.end());
    const std::vector<ExprId> J = jacobian(graph, tau, state);
    FunctionSpec jacobian_spec{"inverse_dynamics_state_jacobian", {}, {"q", "dq", "ddq", "beta"}};
    for (int i = 0; i < dof; ++i) {
      for (int k = 0; k < 3 * dof; ++k) {
        const int index = i * 3 * dof + k;
        const char* array = k < dof ? "q" : (k < 2 * dof ? "dq" : "ddq");
        jacobian_spec.outputs.push_back(
            {"J[" + std::to_string(index) + "]", J[index],
             i == 0 ? std::string(array) + "[" + std::to_string(k % dof) + "]" : std::string()});
      }
    }
    specs.push_back(std::move(jacobian_spec));
  }
  {
    FunctionSpec spec{"base_from_standard", {}, {"p_standard"}};
    for (int b = 0; b < num_base; ++b) {
      std::vector<ExprId> terms;
      for (const auto& [k, coefficient] : base.params[b].relation) {
        terms.push_back(graph.mul(
            graph.constant(coefficient),
            graph.symbol({"p_standard[" + std::to_string(k) + "]", SymbolKind::kInput, ""})));
      }
      spec.outputs.push_back({"beta[" + std::to_string(b) + "]", graph.add(terms),
                              base.params[b].name});
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

  {
    // Power model on the base parameters: the base columns of the standard h and dh.
    const std::vector<ExprId> h = derive_energy_regressor(graph, tree, symbols);
    const std::vector<ExprId> dh = derive_power_regressor(graph, tree, symbols, h);
    FunctionSpec energy{"energy_regressor", {}, {"q", "dq"}};
    FunctionSpec power{"power_regressor", {}, {"q", "dq", "ddq"}};
    for (int b = 0; b < num_base; ++b) {
      const int k = base.params[b].standard_index;
      energy.outputs.push_back({"h[" + std::to_string(b) + "]", h[k], base.params[b].name});
      power.outputs.push_back({"dh[" + std::to_string(b) + "]", dh[k], base.params[b].name});
    }
    specs.push_back(std::move(energy));
    specs.push_back(std::move(power));
  }
  // The Swevers drive model F (eq. 12) and its Jacobians with respect to its parameters theta
  // (eq. 14) and to the state (Bona & Curatella eq. 13-16). The sign terms (friction,
  // efficiency branch) are piecewise constant: their derivative is taken as zero. drive_torque
  // is flattened like the others; the Jacobians call the standard regressor, or the base inverse
  // dynamics and its state Jacobian, into local arrays and apply the chain rule to them, so
  // their bodies stay small (flattened, the state Jacobian alone doubled the compile time of
  // the larger models).
  const DriveParameters drive = make_drive_parameters(graph, tree);
  const int num_drive = static_cast<int>(drive.theta.size());
  const Eigen::MatrixXd V = joint_from_motor(model.drives.motor_from_joint, dof);
  {
    SymbolicInputs rigid = symbols;
    rigid.p = rigid_body_parameters(graph, tree, drive);
    const DriveTorques torques = derive_drive_torques(
        graph, model.drives.motor_from_joint, symbols, drive,
        derive_inverse_dynamics(graph, tree, rigid));
    FunctionSpec spec{"drive_torque", {}, {"q", "dq", "ddq", "theta"}};
    for (int i = 0; i < dof; ++i) {
      spec.outputs.push_back({"tau_M[" + std::to_string(i) + "]", torques.tau_M[i], ""});
    }
    specs.push_back(std::move(spec));
  }
  {
    // tau_G = W_std p with W_std from idim_regressor_standard: F is then an expression of
    // W_std and theta, and d F / d theta its symbolic derivative.
    std::vector<ExprId> tau_G;
    for (int i = 0; i < dof; ++i) {
      std::vector<ExprId> terms;
      for (std::size_t k = 0; k < drive.standard_index.size(); ++k) {
        terms.push_back(graph.mul(
            input_symbol(graph, "W_std", i * num_params + drive.standard_index[k]),
            drive.theta[k]));
      }
      tau_G.push_back(graph.add(std::move(terms)));
    }
    const DriveTorques torques =
        derive_drive_torques(graph, model.drives.motor_from_joint, symbols, drive, tau_G);
    const std::vector<ExprId> J = jacobian(graph, torques.tau_M, drive.theta);
    FunctionSpec spec{"drive_torque_jacobian", {}, {"q", "dq", "ddq", "theta"}};
    // The residual with its Jacobian (what a least-squares solver asks for at once): tau_M
    // from the same W_std and intermediates, no second Newton-Euler pass.
    for (int i = 0; i < dof; ++i) {
      spec.outputs.push_back({"tau_M[" + std::to_string(i) + "]", torques.tau_M[i], ""});
    }
    for (int i = 0; i < dof; ++i) {
      for (int k = 0; k < num_drive; ++k) {
        const int index = i * num_drive + k;
        spec.outputs.push_back({"J[" + std::to_string(index) + "]", J[index],
                                i == 0 ? drive.names[k] : std::string()});
      }
    }
    spec.prologue = [](Scalar scalar) {
      return std::vector<std::string>{
          local_array(scalar, "W_std", "kDof * kStandardParams"),
          call("idim_regressor_standard", "q, dq, ddq, W_std")};
    };
    spec.calls = {"idim_regressor_standard"};
    specs.push_back(std::move(spec));
  }
  {
    // d tau_M / d x = c V^T d tau_G / d x + Rv K (dq block) + JM K (ddq block), with tau_G and
    // d tau_G / d x from the base inverse dynamics and its state Jacobian at
    // beta = base_from_standard(p) (tau = W_std p = W_base beta for every p).
    std::vector<ExprId> tau_G;
    for (int i = 0; i < dof; ++i) tau_G.push_back(input_symbol(graph, "tau_G", i));
    const DriveTorques torques =
        derive_drive_torques(graph, model.drives.motor_from_joint, symbols, drive, tau_G);
    const Eigen::MatrixXd& K = model.drives.motor_from_joint;
    FunctionSpec spec{"drive_torque_state_jacobian", {}, {"q", "dq", "ddq", "theta"}};
    for (int i = 0; i < dof; ++i) {
      for (int k = 0; k < 3 * dof; ++k) {
        std::vector<ExprId> chain;
        for (int j = 0; j < dof; ++j) {
          chain.push_back(graph.mul(graph.constant(V(j, i)),
                                    input_symbol(graph, "dtau_G", j * 3 * dof + k)));
        }
        std::vector<ExprId> terms = {graph.mul(torques.efficiency[i], graph.add(chain))};
        // Eq. 7 and 9: d (Rv dq_M) / d dq = Rv K, d (JM ddq_M) / d ddq = JM K.
        if (k >= dof && k < 2 * dof) {
          terms.push_back(graph.mul(graph.constant(K(i, k - dof)), drive.Rv[i]));
        } else if (k >= 2 * dof) {
          terms.push_back(graph.mul(graph.constant(K(i, k - 2 * dof)), drive.JM[i]));
        }
        const char* array = k < dof ? "q" : (k < 2 * dof ? "dq" : "ddq");
        spec.outputs.push_back(
            {"J[" + std::to_string(i * 3 * dof + k) + "]", graph.add(terms),
             i == 0 ? std::string(array) + "[" + std::to_string(k % dof) + "]" : std::string()});
      }
    }
    spec.prologue = [&drive](Scalar scalar) {
      std::vector<std::string> lines = {local_array(scalar, "p_std", "kStandardParams")};
      for (std::size_t k = 0; k < drive.standard_index.size(); ++k) {
        lines.push_back(render_statement(
            "statements/output",
            {{"target", "p_std[" + std::to_string(drive.standard_index[k]) + "]"},
             {"value", "theta[" + std::to_string(k) + "]"}}));
      }
      lines.push_back(local_array(scalar, "beta", "kBaseParams"));
      lines.push_back(call("base_from_standard", "p_std, beta"));
      lines.push_back(local_array(scalar, "tau_G", "kDof"));
      lines.push_back(call("inverse_dynamics", "q, dq, ddq, beta, tau_G"));
      lines.push_back(local_array(scalar, "dtau_G", "kDof * 3 * kDof"));
      lines.push_back(call("inverse_dynamics_state_jacobian", "q, dq, ddq, beta, dtau_G"));
      return lines;
    };
    spec.calls = {"base_from_standard", "inverse_dynamics", "inverse_dynamics_state_jacobian"};
    specs.push_back(std::move(spec));
  }
  {
    FunctionSpec spec{"joint_sincos", {}, {"q"}};
    for (int i = 0; i < dof; ++i) {
      spec.outputs.push_back({"sin_q[" + std::to_string(i) + "]", symbols.sin_q[i], ""});
      spec.outputs.push_back({"cos_q[" + std::to_string(i) + "]", symbols.cos_q[i], ""});
    }
    specs.push_back(std::move(spec));
  }
  // Variants reading sin/cos from the caller (joint_sincos), for several functions per state.
  // Not for the state Jacobian: its body is several times that of the inverse dynamics, so
  // sharing the sines and cosines would save under 1 % of its work for twice the code to
  // compile. Not for the drive model either (one call per sample in an estimation loop).
  for (std::size_t i = 0, count = specs.size(); i < count; ++i) {
    if (specs[i].name == "joint_sincos" || specs[i].name == "base_from_standard" ||
        specs[i].name == "inverse_dynamics_state_jacobian" ||
        specs[i].name.starts_with("drive_torque")) {
      continue;
    }
    FunctionSpec variant = specs[i];
    variant.name += "_sincos";
    variant.parameters.push_back("sin_q");
    variant.parameters.push_back("cos_q");
    variant.trig = TrigSource::kGiven;
    specs.push_back(std::move(variant));
  }

  // Order of appearance in the generated files: standard-parameter functions, the
  // regrouping, then the base-parameter functions.
  const std::vector<std::string> order = {
      "idim_regressor_standard", "inverse_dynamics_standard", "joint_sincos",
      "idim_regressor_standard_sincos", "inverse_dynamics_standard_sincos", "base_from_standard",
      "idim_regressor", "inverse_dynamics", "idim_regressor_sincos", "inverse_dynamics_sincos",
      "inverse_dynamics_state_jacobian", "energy_regressor", "power_regressor",
      "energy_regressor_sincos", "power_regressor_sincos", "drive_torque", "drive_torque_jacobian",
      "drive_torque_state_jacobian"};
  std::stable_sort(specs.begin(), specs.end(), [&order](const FunctionSpec& a, const FunctionSpec& b) {
    return std::find(order.begin(), order.end(), a.name) < std::find(order.begin(), order.end(), b.name);
  });

  std::vector<EmittedFunction> functions;
  GeneratedModel result;
  for (const FunctionSpec& spec : specs) {
    EmittedFunction f{&spec, {}};
    for (Scalar scalar : input.scalars) {
      FunctionBody body = write_statements(graph, spec.outputs, scalar, spec.trig);
      if (spec.prologue) {
        std::vector<std::string> lines = spec.prologue(scalar);
        lines.insert(lines.end(), body.lines.begin(), body.lines.end());
        body.lines = std::move(lines);
      }
      f.body.push_back(std::move(body));
    }
    OpCounts counts = f.body[0].counts;
    for (const std::string& callee : spec.calls) {
      const auto found = std::find_if(result.functions.begin(), result.functions.end(),
                                      [&](const FunctionReport& r) { return r.name == callee; });
      if (found == result.functions.end()) {
        throw std::logic_error("emit_model: " + spec.name + " calls " + callee +
                               ", which is not emitted before it");
      }
      counts.mul += found->counts.mul;
      counts.add += found->counts.add;
      counts.trig += found->counts.trig;
    }
    result.functions.push_back({spec.name, counts});
    functions.push_back(std::move(f));
  }

  const std::string sha256 = sha256_hex(input.input_bytes);
  // The name column of the banner's operation table fits the longest function name.
  std::size_t name_width = 34;
  for (const FunctionReport& f : result.functions) {
    name_width = std::max(name_width, f.name.size() + 2);
  }
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
                                              .set("function", pad_right(name, name_width))
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

  std::vector<std::string> standard_names, base_names;
  for (const StandardParam& p : tree.params) standard_names.push_back(p.name);
  for (const BaseParameter& b : base.params) base_names.push_back(b.name);

  const std::string header_name = input.stem + ".hpp";
  const std::string source_name = input.stem + ".cpp";
  const std::string header =
      Printer(embedded_template("model.hpp"))
          .set("banner", strip_newline(banner(header_name)))
          .set("include_guard", guard)
          .set("robot", model.name)
          .set("format_version", kFormatVersion)
          // The drive-chain constants take the first scalar type asked for.
          .set("scalar", scalar_name(input.scalars.front()))
          .set("dof", dof)
          .set("standard_param_count", num_params)
          .set("base_param_count", num_base)
          .set("drive_param_count", num_drive)
          .set_block("model_struct",
                     [&](CodeWriter& out) {
                       if (input.scalars.empty() || input.scalars[0] != Scalar::kDouble) return;
                       const std::string text = strip_newline(Printer(embedded_template("model_struct"))
                                                                  .set("robot", model.name)
                                                                  .set("sha256", sha256)
                                                                  .render());
                       std::size_t start = 0;
                       while (start <= text.size()) {
                         std::size_t end = text.find('\n', start);
                         if (end == std::string::npos) end = text.size();
                         out.line(text.substr(start, end - start));
                         start = end + 1;
                       }
                     })
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
          .set("scalar", scalar_name(input.scalars.front()))
          .set_block("standard_param_names",
                     [&](CodeWriter& out) { write_name_list(standard_names, out); })
          .set_block("base_param_names",
                     [&](CodeWriter& out) { write_name_list(base_names, out); })
          .set_block("drive_param_names",
                     [&](CodeWriter& out) { write_name_list(drive.names, out); })
          .set_block("motor_from_joint",
                     [&](CodeWriter& out) {
                       // One row of K per line, so the matrix reads as written.
                       const Eigen::MatrixXd& K = model.drives.motor_from_joint;
                       for (Eigen::Index r = 0; r < K.rows(); ++r) {
                         std::vector<double> row(K.cols());
                         for (Eigen::Index c = 0; c < K.cols(); ++c) row[c] = K(r, c);
                         write_number_list(row, input.scalars.front(), out);
                       }
                     })
          .set_block("torque_constant",
                     [&](CodeWriter& out) { write_number_list(as_vector(model.drives.torque_constant), input.scalars.front(), out); })
          .set_block("joint_offset",
                     [&](CodeWriter& out) { write_number_list(as_vector(model.drives.joint_offset), input.scalars.front(), out); })
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
          .set_block("base_parameters",
                     [&](CodeWriter& out) {
                       for (int b = 0; b < num_base; ++b) {
                         std::string relation;
                         for (const auto& [k, coefficient] : base.params[b].relation) {
                           relation += (relation.empty() ? "" : ", ") +
                                       json_string(tree.params[k].name) + ": " +
                                       json_number(coefficient);
                         }
                         out.line("{\"name\": " + json_string(base.params[b].name) +
                                  ", \"relation\": {" + relation + "}}" +
                                  (b + 1 < num_base ? "," : ""));
                       }
                     })
          .set_block("drive_parameters",
                     [&](CodeWriter& out) {
                       for (int k = 0; k < num_drive; ++k) {
                         out.line(json_string(drive.names[k]) + (k + 1 < num_drive ? "," : ""));
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
