// One build of a description's loadable model: the sibling modelgen generates it (--loadable)
// and the host C++ compiler compiles the files its manifest lists ("loadable_sources") into a
// shared library, in parallel, with every child's output in one log (model_cache.hpp keeps
// the result).
#pragma once

#include <filesystem>
#include <string>

#include "modelgen/model/load_robot.hpp"

namespace modelgen::internal {

/// Optimisation of the loaded model's code. -O1: a 6-axis model's flattened functions compile
/// in a few seconds and run within a few percent of -O2, which takes about twice as long to
/// compile (docs/compiled-models.md has the measurements).
inline constexpr const char* kLoadableCompileFlags = "-std=c++11 -O1 -fPIC";

/// The C++ compiler modelid runs: $CXX when set (it may be several words, "ccache g++"),
/// else c++.
std::string host_compiler();

/// The modelgen that generates a description's model: the one beside the running modelid (an
/// install or a build tree puts them together), else modelgen on PATH.
std::filesystem::path generator_program();

struct ModelBuild {
  std::filesystem::path description;  ///< the description file
  LoadOptions options;                ///< as modelid read it (--angle-tolerance, --name)
  std::filesystem::path folder;       ///< an empty folder of its own for the build's files
  std::filesystem::path library;      ///< the shared library to write (inside `folder`)
  std::filesystem::path log;          ///< where the children's output goes
};

/// What a build gave: `failure` is empty on success, else the step that failed ("modelgen
/// exited with status 1", "the compiler c++ was not found").
struct BuildOutcome {
  std::string failure;
  int compiled_files = 0;
  double seconds = 0;
  bool ok() const { return failure.empty(); }
};

/// Generates and compiles `build`'s model into build.library; never throws for a failing child.
BuildOutcome build_model_library(const ModelBuild& build);

}  // namespace modelgen::internal
