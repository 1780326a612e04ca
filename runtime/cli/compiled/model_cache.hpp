// The compiled models of description files, kept between runs: modelid generates and compiles a
// description's model on first use (model_build.hpp) and loads it (ModelLibrary) from the cache
// after. The cache key is the description's content, the options that change the model, the
// modelgen and modelid that made it and the compiler with its flags; two modelid processes
// share it safely (a lock; one compiles, the other waits and loads); a library is only ever
// renamed into place whole; a corrupted or foreign entry is rebuilt; and whatever fails, the
// caller gets the numeric reference with one line on stderr saying why and what it costs.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/load_robot.hpp"
#include "modelgen/model/model_library.hpp"

namespace modelgen::internal {

/// $MODELGEN_CACHE_DIR when set, else $XDG_CACHE_HOME/modelgen, else $HOME/.cache/modelgen;
/// empty when none of them is set.
std::filesystem::path model_cache_folder();

/// A description file as modelid read it.
struct DescriptionToCompile {
  std::filesystem::path path;
  LoadOptions options;
  /// The description's SHA-256 and the numeric reference made from it: the loaded library
  /// must carry the one and agree with the other (names, sizes, regressor at fixed states).
  const IdentificationModel* reference = nullptr;
};

/// The description's compiled model, built and cached on first use; nullopt, after a note on
/// stderr naming the reason (and the compiler log when there is one), when it cannot be had.
std::optional<ModelLibrary> compiled_model(const DescriptionToCompile& description);

/// The text of the cache key (what changes the compiled model), one "name value" per line; the
/// key is the first 24 hex digits of its SHA-256.
std::string cache_key_text(const DescriptionToCompile& description);

}  // namespace modelgen::internal
