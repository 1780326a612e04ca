// One robot's generated files: the base parameters, the registry's functions on one shared DAG,
// then header, source and manifest rendered from them.

#include "generator/emit/model_emitter.hpp"

#include <algorithm>

#include "generator/dynamics/drive_model.hpp"
#include "generator/emit/function_emitter.hpp"
#include "generator/emit/header_file.hpp"
#include "generator/emit/manifest_file.hpp"
#include "generator/emit/render_input.hpp"
#include "generator/emit/source_file.hpp"
#include "modelgen/model/base_parameters.hpp"
#include "modelgen/model/sha256.hpp"

namespace modelgen::gen {

namespace {

// The estimate's values in base-parameter order, refused when they do not fit the model or,
// with float entry points, a float.
std::vector<double> identified_values(const EstimateFile& estimate, const RobotModel& model,
                                      const BaseParameterSet& base,
                                      const std::vector<Scalar>& scalars) {
  std::vector<std::string> names;
  for (const BaseParameter& b : base.params) names.push_back(b.name);
  std::vector<double> values = base_values(estimate, names, model.name);
  for (Scalar scalar : scalars) {
    if (scalar == Scalar::kFloat) check_fits_float(estimate);
  }
  return values;
}

}  // namespace

GeneratedModel emit_model(const RobotModel& model, const GenerationInput& input) {
  const BaseParameterSet base = derive_base_parameters(model.tree);
  // The estimate is checked before the (longer) derivation of the functions.
  std::vector<double> identified;
  if (input.estimate) identified = identified_values(*input.estimate, model, base, input.scalars);
  ExprGraph graph;
  GeneratedModel result;
  RenderInput in{model,
                 input,
                 base,
                 {},
                 sha256_hex(input.input_bytes),
                 emit_functions(model, base, graph, input.scalars, input.estimate.has_value(),
                                input.functions, &result.added_callees),
                 std::move(identified)};
  in.drive_param_names = make_drive_parameters(graph, model.tree).names;

  result.notes = model.notes;
  if (input.estimate) result.warnings = input.estimate->warnings;
  for (const EmittedFunction& f : in.functions) result.functions.push_back({f.name, f.counts});
  result.files.add(in.header_name(), render_header(in));
  result.files.add(in.source_name(), render_source(in));
  for (const EmittedFunction& f : in.functions) {
    result.files.add(in.function_source_name(f.name), render_function_source(in, f));
  }
  result.files.add(in.manifest_name(), render_manifest(in));
  // Function files of this stem that an earlier run may have made: gone once the set is written.
  for (const std::string& name : entry_point_names(true)) {
    const std::string file = in.function_source_name(name);
    const auto& files = result.files.files();
    if (std::none_of(files.begin(), files.end(), [&](const OutputFile& f) { return f.name == file; })) {
      result.files.retire(file);
    }
  }
  return result;
}

}  // namespace modelgen::gen
