// One call from a description file to the generated files in memory: what `modelgen ROBOT -o
// DIR` does before writing, shared with the tests that regenerate generated/ in-process.
#pragma once

#include <string>
#include <vector>

#include "modelgen/model/load_robot.hpp"
#include "generator/emit/model_emitter.hpp"

namespace modelgen::gen {

/// What a run generates besides the description's model (modelgen's options other than those
/// of LoadOptions).
struct GenerationOptions {
  /// "both" (double and float entry points), "double" or "float".
  std::string scalar = "both";
  /// When not empty, an estimate of `modelid fit -o` whose base parameters become constants
  /// and inverse_dynamics_identified (firmware values).
  std::string params_path = {};
  /// When not empty, the entry points to generate (--functions; the ones they call come too).
  std::vector<std::string> functions = {};
  /// Also STEM_loadable.cpp, the C entry point of a shared library of the model (--loadable);
  /// needs every function and double entry points first.
  bool loadable = false;
};

/// Loads `robot_path` and emits its model. The output file stem is the description's file name
/// without extension; the banner's command line is normalized (file name only, options that
/// change the output in a fixed order). Throws InputError for a bad description, a bad or
/// foreign estimate; UsageError for a function name that is not one, or --loadable with
/// --functions or --scalar float.
GeneratedModel generate_from_file(const std::string& robot_path, const LoadOptions& options,
                                  const GenerationOptions& generation = {});

/// "modelgen kr150.yaml -o <dir>" plus --name/--base/--tip/--scalar/--angle-tolerance/--params/
/// --functions/--loadable when not the default, in that order (--params by file name only, as
/// the description; --functions in file order).
std::string normalized_command(const std::string& robot_path, const LoadOptions& options,
                               const GenerationOptions& generation = {});

}  // namespace modelgen::gen
