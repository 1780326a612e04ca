// Runs the builders of the registry on one model and writes the statements of every entry
// point (the _sincos variants included) for each scalar type, in the order of the files.
#pragma once

#include <string>
#include <vector>

#include "generator/emit/statement_writer.hpp"
#include "generator/functions/entry_points.hpp"
#include "generator/functions/function_entry.hpp"
#include "generator/symbolic/expr.hpp"
#include "modelgen/model/base_parameters.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::gen {

/// The entries of one output array that are zero for every input, which the function does not
/// write (the caller zeroes the array once).
struct UnwrittenEntries {
  std::string array;
  int total = 0;             ///< the array's size
  std::vector<int> indices;  ///< ascending
};

struct EmittedFunction {
  std::string name;  ///< the entry point: the registry name, suffixed _sincos for a variant
  const FunctionEntry* entry = nullptr;
  bool sincos = false;
  /// The input arrays, in the order of the parameter list (a variant's sin_q, cos_q after q).
  std::vector<std::string> inputs;
  std::vector<std::string> outputs;  ///< the output arrays, after the inputs
  std::vector<std::string> calls;    ///< entry points the body calls, which come before it
  std::vector<FunctionBody> bodies;  ///< one per scalar type asked for, in that order
  OpCounts counts;                   ///< of the body, plus those of the entry points it calls
  std::vector<UnwrittenEntries> unwritten;  ///< per output array with entries left unwritten
};

/// The entry points `generated` (select_functions' choice, in file order), for each scalar
/// type; only their builders run. `drive_regressor_index` receives the packed drive
/// regressor's layout (the dense index of each entry, build_context.hpp's
/// drive_regressor_entries), whatever the selection. Throws std::logic_error when a builder
/// writes more or fewer values than its entry declares.
std::vector<EmittedFunction> emit_functions(const RobotModel& model, const BaseParameterSet& base,
                                            ExprGraph& graph, const std::vector<Scalar>& scalars,
                                            const std::vector<EntryPoint>& generated,
                                            std::vector<int>* drive_regressor_index = nullptr);

/// Every entry point of a model `with_estimate` or not (entry_points()), as above.
std::vector<EmittedFunction> emit_functions(const RobotModel& model, const BaseParameterSet& base,
                                            ExprGraph& graph, const std::vector<Scalar>& scalars,
                                            bool with_estimate = false);

}  // namespace modelgen::gen
