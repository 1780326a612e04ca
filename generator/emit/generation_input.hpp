// What, besides the robot model, goes into the generated files.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "generator/emit/number_format.hpp"
#include "generator/estimate/estimate_file.hpp"
#include "generator/functions/entry_points.hpp"

namespace modelgen::gen {

struct GenerationInput {
  std::string stem;          ///< output file stem, from the description file name: "kr150"
  std::string input_name;    ///< description file name without directories: "kr150.yaml"
  std::string input_bytes;   ///< the description exactly as read (hashed)
  std::string command_line;  ///< normalized: only options that change the output, fixed order
  /// Scalar types to emit entry points for, in this order (double first when both).
  std::vector<Scalar> scalars = {Scalar::kDouble, Scalar::kFloat};
  /// The estimate of --params, whose base parameters become constants and
  /// inverse_dynamics_identified; none without it.
  std::optional<EstimateFile> estimate;
  /// The entry points to generate (select_functions of --functions).
  FunctionSelection functions;
  /// Also STEM_loadable.cpp, the C entry point of a shared library of the model (--loadable;
  /// every function generated, double first).
  bool loadable = false;
};

}  // namespace modelgen::gen
