// Everything the generated header, source and manifest are rendered from: the model, its base
// and drive parameters, the input's facts and the emitted functions.
#pragma once

#include <string>
#include <vector>

#include "generator/emit/function_emitter.hpp"
#include "generator/emit/generation_input.hpp"
#include "modelgen/model/base_parameters.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::gen {

struct RenderInput {
  const RobotModel& model;
  const GenerationInput& input;
  const BaseParameterSet& base;
  std::vector<std::string> drive_param_names;  ///< theta of drive_torque, in order
  /// The dense index (row-major kDof x kDriveParams) of each entry of the packed drive
  /// regressor Y, in order (build_context.hpp's drive_regressor_entries).
  std::vector<int> drive_regressor_index;
  std::string sha256;                          ///< of input.input_bytes, 64 hex digits
  std::vector<EmittedFunction> functions;      ///< in the order of the generated files
  /// The estimate's values (--params) in the order of base.params; empty without an estimate.
  std::vector<double> identified_base = {};

  std::string header_name() const { return input.stem + ".hpp"; }
  std::string source_name() const { return input.stem + ".cpp"; }
  /// The file of one entry point: "tx40_inverse_dynamics.cpp".
  std::string function_source_name(const std::string& function) const {
    return input.stem + "_" + function + ".cpp";
  }
  std::string manifest_name() const { return input.stem + ".json"; }
  /// The C entry point of a model built as a shared library (--loadable).
  std::string loadable_name() const { return input.stem + "_loadable.cpp"; }
};

}  // namespace modelgen::gen
