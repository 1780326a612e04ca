// One call from a description file to the generated files in memory: what `modelgen ROBOT -o
// DIR` does before writing, shared with the tests that regenerate generated/ in-process.
#pragma once

#include <string>
#include <vector>

#include "modelgen/model/load_robot.hpp"
#include "generator/emit/model_emitter.hpp"

namespace modelgen::gen {

/// Loads `robot_path` and emits its model. The output file stem is the description's file name
/// without extension; the banner's command line is normalized (file name only, options that
/// change the output in a fixed order). Throws InputError for a bad description.
/// `scalar` is "both" (double and float entry points), "double" or "float". `params_path`, when
/// not empty, is an estimate of `modelid fit -o` whose base parameters become constants and
/// inverse_dynamics_identified (firmware values); InputError for a bad or foreign estimate.
/// `functions`, when not empty, are the entry points to generate (--functions; the ones they
/// call come too); UsageError for a name that is not one.
GeneratedModel generate_from_file(const std::string& robot_path, const LoadOptions& options,
                                  const std::string& scalar = "both",
                                  const std::string& params_path = "",
                                  const std::vector<std::string>& functions = {});

/// "modelgen kr150.yaml -o <dir>" plus --name/--base/--tip/--scalar/--angle-tolerance/--params/
/// --functions when not the default, in that order (--params by file name only, as the
/// description; --functions in file order).
std::string normalized_command(const std::string& robot_path, const LoadOptions& options,
                               const std::string& scalar = "both",
                               const std::string& params_path = "",
                               const std::vector<std::string>& functions = {});

}  // namespace modelgen::gen
