// Models compiled at build time for machines without a compiler at run time: shared libraries
// made by modelgen_generate(... LOADABLE) (docs/compiled-models.md), found in the folders of
// $MODELGEN_MODEL_PATH and in the install's lib/modelgen/models, used for the description whose
// SHA-256 their table carries once they agree with its numeric reference.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "modelgen/model/model_library.hpp"
#include "runtime/cli/compiled/model_cache.hpp"

namespace modelgen::internal {

/// The folders searched, in order: those of $MODELGEN_MODEL_PATH (separated by ':'), then
/// lib/modelgen/models beside the folder of the running modelid (bin/../lib/modelgen/models).
std::vector<std::filesystem::path> prebuilt_model_folders();

/// The first library (*.so) of those folders made from `description` and agreeing with its
/// reference; nullopt when there is none. Libraries of other descriptions are passed over
/// silently.
std::optional<ModelLibrary> prebuilt_model(const DescriptionToCompile& description);

}  // namespace modelgen::internal
