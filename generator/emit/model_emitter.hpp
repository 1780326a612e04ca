// Builds the generated files of one robot: NAME.hpp, NAME.cpp and the manifest NAME.json, from
// the symbolic derivations, the statement writer and the templates.
#pragma once

#include <string>
#include <vector>

#include "modelgen/model/robot_model.hpp"
#include "generator/emit/statement_writer.hpp"
#include "generator/output/file_set.hpp"

namespace modelgen::gen {

/// What, besides the model, goes into the generated files.
struct GenerationInput {
  std::string stem;          ///< output file stem, from the description file name: "kr150"
  std::string input_name;    ///< description file name without directories: "kr150.yaml"
  std::string input_bytes;   ///< the description exactly as read (hashed)
  std::string command_line;  ///< normalized: only options that change the output, fixed order
  /// Scalar types to emit entry points for, in this order (double first when both).
  std::vector<Scalar> scalars = {Scalar::kDouble, Scalar::kFloat};
};

/// Operation counts of one generated function (double and float bodies are the same code),
/// including those of the entry points it calls (the drive model Jacobians call others).
struct FunctionReport {
  std::string name;
  OpCounts counts;
};

struct GeneratedModel {
  FileSet files;
  std::vector<FunctionReport> functions;
};

/// Format of the generated interface; bump when the generated API changes incompatibly.
inline constexpr int kFormatVersion = 3;

GeneratedModel emit_model(const RobotModel& model, const GenerationInput& input);

}  // namespace modelgen::gen
