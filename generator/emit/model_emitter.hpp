// Builds the generated files of one robot: NAME.hpp, NAME.cpp (tables), NAME_<function>.cpp
// per entry point and the manifest NAME.json, from the registry of generated functions, the
// statement writer and the templates.
#pragma once

#include <string>
#include <vector>

#include "generator/emit/generation_input.hpp"
#include "generator/emit/statement_writer.hpp"
#include "generator/output/file_set.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::gen {

/// Operation counts of one generated function (double and float bodies are the same code),
/// including those of the entry points it calls (the drive model Jacobians call others).
struct FunctionReport {
  std::string name;
  OpCounts counts;
};

struct GeneratedModel {
  FileSet files;
  std::vector<FunctionReport> functions;  ///< in the order of the generated files
  std::vector<DescriptionNote> notes;     ///< what the loader snapped (RobotModel::notes)
  std::vector<std::string> warnings;      ///< about the estimate, as printed ("PATH: warning: ...")
  /// Entry points generated although --functions did not name them, because a chosen one
  /// calls them: "drive_torque_jacobian calls idim_regressor_standard".
  std::vector<std::string> added_callees;
};

GeneratedModel emit_model(const RobotModel& model, const GenerationInput& input);

}  // namespace modelgen::gen
