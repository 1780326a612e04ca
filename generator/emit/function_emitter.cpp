// The registry run on one model: builders in registry order on one shared DAG, then each entry
// point's statements for every scalar type, the operation counts of called entry points added.

#include "generator/emit/function_emitter.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "generator/dynamics/drive_model.hpp"
#include "generator/functions/build_context.hpp"
#include "generator/functions/registry.hpp"
#include "modelgen/model/command_line.hpp"

namespace modelgen::gen {

namespace {

std::string entry_point_name(const FunctionEntry& entry, bool sincos) {
  return std::string(entry.name) + (sincos ? "_sincos" : "");
}

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

std::vector<Built> run_builders(const RobotModel& model, const BaseParameterSet& base,
                                ExprGraph& graph, const std::vector<Scalar>& scalars,
                                bool with_estimate) {
  BuildContext context{model, base, graph, make_symbolic_inputs(graph, model.tree), scalars};
  std::vector<Built> built;
  for (const FunctionEntry& entry : function_registry()) {
    if (entry.emitted == Emitted::kWithEstimate && !with_estimate) continue;
    built.push_back({&entry, entry.build(context)});
  }
  const ModelSizes sizes{model.tree.dof, context.num_params(), context.num_base(),
                         static_cast<int>(make_drive_parameters(graph, model.tree).theta.size())};
  for (const Built& b : built) check_output_count(b, sizes);
  return built;
}

// The entry point of `built` (plain or _sincos) with its statements for every scalar type.
EmittedFunction emit(const Built& built, bool sincos, const ExprGraph& graph,
                     const std::vector<Scalar>& scalars) {
  EmittedFunction function;
  function.name = entry_point_name(*built.entry, sincos);
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
  for (Scalar scalar : scalars) {
    FunctionBody body = write_statements(graph, definition.outputs, scalar,
                                         sincos ? TrigSource::kGiven : TrigSource::kCompute);
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

// File order: by section; in a section the plain functions, then the _sincos variants, each
// in registry order.
template <typename Item, typename EntryOf>
std::vector<std::pair<const Item*, bool>> file_order(const std::vector<Item>& items,
                                                     EntryOf entry_of) {
  std::vector<std::pair<const Item*, bool>> order;
  for (const Item& item : items) order.push_back({&item, false});
  for (const Item& item : items) {
    if (entry_of(item).variants == Variants::kSincos) order.push_back({&item, true});
  }
  std::stable_sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
    return std::make_pair(entry_of(*a.first).section, a.second) <
           std::make_pair(entry_of(*b.first).section, b.second);
  });
  return order;
}

// The names of `selection` and, transitively, the entry points their bodies call.
std::set<std::string> with_callees(const std::vector<std::string>& selection,
                                   const std::vector<Built>& built,
                                   std::vector<std::string>* added) {
  std::set<std::string> kept(selection.begin(), selection.end());
  std::vector<std::string> pending(selection.begin(), selection.end());
  while (!pending.empty()) {
    const std::string name = pending.back();
    pending.pop_back();
    for (const Built& b : built) {
      // A variant calls what its plain function calls.
      if (name != b.entry->name && name != entry_point_name(*b.entry, true)) continue;
      for (const std::string& callee : b.entry->calls) {
        if (!kept.insert(callee).second) continue;
        pending.push_back(callee);
        if (added != nullptr) added->push_back(name + " calls " + callee);
      }
    }
  }
  return kept;
}

void check_selection(const std::vector<std::string>& selection, bool with_estimate) {
  const std::vector<std::string> valid = entry_point_names(with_estimate);
  for (const std::string& name : selection) {
    if (std::find(valid.begin(), valid.end(), name) != valid.end()) continue;
    if (!with_estimate) {
      const std::vector<std::string> all = entry_point_names(true);
      if (std::find(all.begin(), all.end(), name) != all.end()) {
        throw UsageError("--functions: " + name + " uses identified constants; it needs --params");
      }
    }
    std::string list;
    for (const std::string& v : valid) list += (list.empty() ? "" : ", ") + v;
    throw UsageError("--functions: unknown function '" + name + "'" + did_you_mean(name, valid) +
                     "; the functions are: " + list);
  }
}

}  // namespace

std::vector<std::string> entry_point_names(bool with_estimate) {
  std::vector<FunctionEntry> entries;
  for (const FunctionEntry& entry : function_registry()) {
    if (entry.emitted == Emitted::kAlways || with_estimate) entries.push_back(entry);
  }
  std::vector<std::string> names;
  for (const auto& [entry, sincos] :
       file_order(entries, [](const FunctionEntry& e) -> const FunctionEntry& { return e; })) {
    names.push_back(entry_point_name(*entry, sincos));
  }
  return names;
}

std::string entry_point_list() {
  std::string text;
  for (const std::string& name : entry_point_names(true)) {
    text += name;
    for (const FunctionEntry& entry : function_registry()) {
      if (name != entry.name && name != entry_point_name(entry, true)) continue;
      for (std::size_t i = 0; i < entry.calls.size(); ++i) {
        text += (i == 0 ? ":" : ",") + entry.calls[i];
      }
    }
    text += "\n";
  }
  return text;
}

std::vector<EmittedFunction> emit_functions(const RobotModel& model, const BaseParameterSet& base,
                                            ExprGraph& graph, const std::vector<Scalar>& scalars,
                                            bool with_estimate,
                                            const std::vector<std::string>& selection,
                                            std::vector<std::string>* added) {
  check_selection(selection, with_estimate);
  // Every builder runs, so that the callees of the selection are known; only the entry points
  // kept are written, which is most of the work.
  const std::vector<Built> built = run_builders(model, base, graph, scalars, with_estimate);
  const std::set<std::string> kept = with_callees(selection, built, added);
  std::vector<EmittedFunction> functions;
  for (const auto& [b, sincos] :
       file_order(built, [](const Built& item) -> const FunctionEntry& { return *item.entry; })) {
    if (!selection.empty() && kept.count(entry_point_name(*b->entry, sincos)) == 0) continue;
    functions.push_back(emit(*b, sincos, graph, scalars));
  }
  add_callee_counts(functions);
  return functions;
}

}  // namespace modelgen::gen
