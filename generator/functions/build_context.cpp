// Helpers shared by the builders of generated functions.

#include "generator/functions/build_context.hpp"

#include <algorithm>

#include "generator/emit/printer.hpp"

namespace modelgen::gen {

std::string element(const std::string& array, int index) {
  return array + "[" + std::to_string(index) + "]";
}

ExprId input_symbol(ExprGraph& graph, const std::string& array, int index) {
  return graph.symbol({element(array, index), SymbolKind::kInput, ""});
}

SymbolicInputs base_parameter_inputs(BuildContext& context) {
  SymbolicInputs inputs = context.symbols;
  std::fill(inputs.p.begin(), inputs.p.end(), context.graph.zero());
  for (int b = 0; b < context.num_base(); ++b) {
    inputs.p[context.base.params[b].standard_index] = input_symbol(context.graph, "beta", b);
  }
  return inputs;
}

std::vector<ExprId> state_symbols(const SymbolicInputs& symbols) {
  std::vector<ExprId> state = symbols.q;
  state.insert(state.end(), symbols.dq.begin(), symbols.dq.end());
  state.insert(state.end(), symbols.ddq.begin(), symbols.ddq.end());
  return state;
}

std::string state_name(int k, int dof) {
  const char* array = k < dof ? "q" : (k < 2 * dof ? "dq" : "ddq");
  return element(array, k % dof);
}

std::vector<FunctionOutput> row_major_outputs(const std::string& array, int rows, int cols,
                                              const std::function<ExprId(int, int)>& value,
                                              const std::function<std::string(int)>& column_name) {
  std::vector<FunctionOutput> outputs;
  for (int i = 0; i < rows; ++i) {
    for (int k = 0; k < cols; ++k) {
      outputs.push_back({element(array, i * cols + k), value(i, k),
                         i == 0 && column_name ? column_name(k) : std::string()});
    }
  }
  return outputs;
}

std::vector<FunctionOutput> vector_outputs(const std::string& array,
                                           const std::vector<ExprId>& values) {
  std::vector<FunctionOutput> outputs;
  for (std::size_t i = 0; i < values.size(); ++i) {
    outputs.push_back({element(array, static_cast<int>(i)), values[i], ""});
  }
  return outputs;
}

std::vector<ExprId> drive_regressor_on_standard_inputs(BuildContext& context,
                                                       const DriveParameters& drive) {
  ExprGraph& graph = context.graph;
  const std::vector<ExprId> symbolic =
      derive_standard_regressor(graph, context.tree(), context.symbols);
  std::vector<ExprId> W(symbolic.size(), graph.zero());
  for (std::size_t k = 0; k < W.size(); ++k) {
    if (!graph.is_zero(symbolic[k])) W[k] = input_symbol(graph, "W_std", static_cast<int>(k));
  }
  return derive_drive_regressor(graph, context.model.drives.motor_from_joint, context.symbols,
                                drive, W);
}

std::vector<int> drive_regressor_entries(const std::vector<ExprId>& dense_Y,
                                         const ExprGraph& graph) {
  std::vector<int> entries;
  for (std::size_t k = 0; k < dense_Y.size(); ++k) {
    if (!graph.is_zero(dense_Y[k])) entries.push_back(static_cast<int>(k));
  }
  return entries;
}

std::vector<int> drive_regressor_entries(BuildContext& context) {
  const DriveParameters drive = make_drive_parameters(context.graph, context.tree());
  return drive_regressor_entries(drive_regressor_on_standard_inputs(context, drive), context.graph);
}

std::vector<ExprId> drive_regressor_input(BuildContext& context, const DriveParameters& drive) {
  std::vector<ExprId> Y = drive_regressor_on_standard_inputs(context, drive);
  const std::vector<int> entries = drive_regressor_entries(Y, context.graph);
  std::fill(Y.begin(), Y.end(), context.graph.zero());
  for (std::size_t p = 0; p < entries.size(); ++p) {
    Y[static_cast<std::size_t>(entries[p])] = input_symbol(context.graph, "Y", static_cast<int>(p));
  }
  return Y;
}

std::string local_array(Scalar scalar, const std::string& name, const std::string& size) {
  return render_statement("statements/local_array",
                          {{"scalar", scalar_name(scalar)}, {"name", name}, {"size", size}});
}

std::string call(const std::string& function, const std::string& arguments) {
  return render_statement("statements/call", {{"function", function}, {"arguments", arguments}});
}

}  // namespace modelgen::gen
