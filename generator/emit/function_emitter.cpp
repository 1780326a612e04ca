// The registry run on one model: the builders of the chosen entry points in registry order on
// one shared DAG, then each entry point's statements for every scalar type, the operation counts
// of called entry points added.

#include "generator/emit/function_emitter.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "generator/dynamics/drive_model.hpp"
#include "generator/functions/build_context.hpp"
#include "generator/functions/entry_points.hpp"
#include "generator/functions/registry.hpp"
#include "generator/symbolic/output_simplifier.hpp"

namespace modelgen::gen {

namespace {

struct Built {
  const FunctionEntry* entry;
  FunctionDefinition definition;
};

void check_output_count(const Built& built, const ModelSizes& sizes) {
  int expected = 0;
  // A wrapper's outputs are written by the entry point it calls.
  if (!built.definition.outputs_written_by_call) {
    for (const ArraySpec& array : built.entry->outputs) expected += array_size(array, sizes);
  }
  const int written = static_cast<int>(built.definition.outputs.size());
  if (written != expected) {
    throw std::logic_error(std::string("emit_functions: the builder of ") + built.entry->name +
                           " writes " + std::to_string(written) + " values, its entry declares " +
                           std::to_string(expected));
  }
}

// The entries of `array` (an output of `built`) that are the constant 0. The builders write
// each array's entries in index order (row_major_outputs, vector_outputs).
std::vector<int> zero_entries(const Built& built, const std::string& array, const ExprGraph& graph,
                              const ModelSizes& sizes) {
  std::vector<int> zeros;
  std::size_t next = 0;
  for (const ArraySpec& spec : built.entry->outputs) {
    const int size = array_size(spec, sizes);
    if (array == spec.name && !built.definition.outputs_written_by_call) {
      for (int k = 0; k < size; ++k) {
        if (graph.is_zero(built.definition.outputs[next + k].value)) zeros.push_back(k);
      }
    }
    next += static_cast<std::size_t>(size);
  }
  return zeros;
}

// The builders of the chosen entry points and of the functions whose outputs they read
// (FunctionDefinition::reads; built, not emitted), in registry order, their outputs simplified
// (exact zeros removed, sign-normal form: output_simplifier.hpp) and the entries they read that
// their writer never writes replaced by 0. Operand order depends on structure only
// (ExprGraph), so a body is the same whichever builders ran before it. Also gives the packed
// drive regressor's layout (drive_regressor_entries).
std::vector<Built> run_builders(const RobotModel& model, const BaseParameterSet& base,
                                ExprGraph& graph, const std::vector<Scalar>& scalars,
                                const std::vector<EntryPoint>& chosen, ModelSizes& sizes,
                                std::vector<int>& drive_regressor_index) {
  BuildContext context{model, base, graph, make_symbolic_inputs(graph, model.tree), scalars};
  const std::vector<FunctionEntry>& registry = function_registry();
  std::vector<bool> needed(registry.size(), false);
  for (std::size_t i = 0; i < registry.size(); ++i) {
    needed[i] = std::any_of(chosen.begin(), chosen.end(),
                            [&](const EntryPoint& p) { return p.entry == &registry[i]; });
  }
  std::vector<std::optional<FunctionDefinition>> definitions(registry.size());
  // Readers come after the functions they read in the registry: build from the end, adding
  // each reader's writers to what is needed.
  for (std::size_t i = registry.size(); i-- > 0;) {
    if (!needed[i]) continue;
    definitions[i] = registry[i].build(context);
    for (const FunctionDefinition::ReadsOutput& read : definitions[i]->reads) {
      const auto writer =
          std::find_if(registry.begin(), registry.end(),
                       [&](const FunctionEntry& e) { return read.function == e.name; });
      if (writer == registry.end() || writer - registry.begin() >= static_cast<std::ptrdiff_t>(i)) {
        throw std::logic_error(std::string("emit_functions: ") + registry[i].name + " reads " +
                               read.function + ", which is not before it in the registry");
      }
      needed[static_cast<std::size_t>(writer - registry.begin())] = true;
    }
  }
  std::vector<Built> built;
  for (std::size_t i = 0; i < registry.size(); ++i) {
    if (definitions[i]) built.push_back({&registry[i], std::move(*definitions[i])});
  }
  sizes = {model.tree.dof, context.num_params(), context.num_base(),
           static_cast<int>(make_drive_parameters(graph, model.tree).theta.size())};
  // The packed layout whatever the selection: the header declares it and sizes Y by it. It only
  // adds shared nodes to the graph (no simplifier runs before this point), so the bodies stay
  // those of the full run (ModelgenCli.AFunctionGeneratedAloneHasTheCodeOfTheFullRun).
  drive_regressor_index = drive_regressor_entries(context);
  sizes.drive_regressor_entries = static_cast<int>(drive_regressor_index.size());
  for (const Built& b : built) check_output_count(b, sizes);
  OutputSimplifier simplify(graph);
  for (std::size_t i = 0; i < built.size(); ++i) {
    FunctionDefinition& definition = built[i].definition;
    std::vector<ExprId> values;
    for (const FunctionOutput& output : definition.outputs)
      values.push_back(simplify(output.value));
    std::vector<ExprId> zero_leaves;
    for (const FunctionDefinition::ReadsOutput& read : definition.reads) {
      const auto writer =
          std::find_if(built.begin(), built.begin() + static_cast<std::ptrdiff_t>(i),
                       [&](const Built& b) { return read.function == b.entry->name; });
      for (int k : zero_entries(*writer, read.output, graph, sizes)) {
        zero_leaves.push_back(input_symbol(graph, read.array, k));
      }
    }
    values = simplify.with_zero_leaves(values, zero_leaves);
    for (std::size_t k = 0; k < values.size(); ++k) definition.outputs[k].value = values[k];
  }
  return built;
}

// The outputs that are the constant 0, which the statement writer leaves out, per array.
std::vector<UnwrittenEntries> unwritten_entries(const Built& built, const ExprGraph& graph,
                                                const ModelSizes& sizes) {
  std::vector<UnwrittenEntries> result;
  for (const ArraySpec& array : built.entry->outputs) {
    UnwrittenEntries entries{array.name, array_size(array, sizes),
                             zero_entries(built, array.name, graph, sizes)};
    if (!entries.indices.empty()) result.push_back(std::move(entries));
  }
  return result;
}

// The entry point of `built` (plain or _sincos) with its statements for every scalar type.
EmittedFunction emit(const Built& built, bool sincos, const ExprGraph& graph,
                     const std::vector<Scalar>& scalars, const ModelSizes& sizes,
                     WriterWorkspace& workspace) {
  EmittedFunction function;
  function.name = EntryPoint{built.entry, sincos}.name();
  function.entry = built.entry;
  function.sincos = sincos;
  function.calls = built.entry->calls;
  for (const ArraySpec& array : built.entry->inputs) {
    function.inputs.push_back(array.name);
    // The variant reads sin(q) and cos(q) from the caller (joint_sincos) in place of computing.
    if (sincos && std::string(array.name) == "q") {
      function.inputs.push_back("sin_q");
      function.inputs.push_back("cos_q");
    }
  }
  for (const ArraySpec& array : built.entry->outputs) function.outputs.push_back(array.name);
  const FunctionDefinition& definition = built.definition;
  function.unwritten = unwritten_entries(built, graph, sizes);
  for (Scalar scalar : scalars) {
    FunctionBody body =
        write_statements(graph, definition.outputs, scalar,
                         sincos ? TrigSource::kGiven : TrigSource::kCompute, workspace);
    if (definition.prologue) {
      std::vector<std::string> lines = definition.prologue(scalar);
      lines.insert(lines.end(), body.lines.begin(), body.lines.end());
      body.lines = std::move(lines);
    }
    function.bodies.push_back(std::move(body));
  }
  function.counts = function.bodies.front().counts;
  return function;
}

// Adds to each function the counts of the entry points it calls, which come before it.
void add_callee_counts(std::vector<EmittedFunction>& functions) {
  for (auto function = functions.begin(); function != functions.end(); ++function) {
    for (const std::string& callee : function->calls) {
      const auto found = std::find_if(functions.begin(), function,
                                      [&](const EmittedFunction& f) { return f.name == callee; });
      if (found == function) {
        throw std::logic_error("emit_functions: " + function->name + " calls " + callee +
                               ", which is not emitted before it");
      }
      function->counts.mul += found->counts.mul;
      function->counts.add += found->counts.add;
      function->counts.trig += found->counts.trig;
    }
  }
}

}  // namespace

std::vector<EmittedFunction> emit_functions(const RobotModel& model, const BaseParameterSet& base,
                                            ExprGraph& graph, const std::vector<Scalar>& scalars,
                                            const std::vector<EntryPoint>& generated,
                                            std::vector<int>* drive_regressor_index) {
  ModelSizes sizes;
  std::vector<int> index;
  const std::vector<Built> built =
      run_builders(model, base, graph, scalars, generated, sizes, index);
  if (drive_regressor_index) *drive_regressor_index = std::move(index);
  std::vector<EmittedFunction> functions;
  WriterWorkspace workspace;
  for (const EntryPoint& point : generated) {
    const auto b = std::find_if(built.begin(), built.end(),
                                [&](const Built& item) { return item.entry == point.entry; });
    functions.push_back(emit(*b, point.sincos, graph, scalars, sizes, workspace));
  }
  add_callee_counts(functions);
  return functions;
}

std::vector<EmittedFunction> emit_functions(const RobotModel& model, const BaseParameterSet& base,
                                            ExprGraph& graph, const std::vector<Scalar>& scalars,
                                            bool with_estimate) {
  return emit_functions(model, base, graph, scalars, entry_points(with_estimate));
}

}  // namespace modelgen::gen
