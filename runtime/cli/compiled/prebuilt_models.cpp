// Each candidate is opened and checked as a cache entry is (ModelLibrary::open refuses another
// description's SHA-256 before anything of it is used); a folder that does not exist is skipped.

#include "runtime/cli/compiled/prebuilt_models.hpp"

#include <cstdlib>
#include <sstream>
#include <string>

#include "runtime/cli/compiled/reference_agreement.hpp"

namespace modelgen::internal {

namespace fs = std::filesystem;

std::vector<fs::path> prebuilt_model_folders() {
  std::vector<fs::path> folders;
  if (const char* path = std::getenv("MODELGEN_MODEL_PATH")) {
    std::istringstream in(path);
    for (std::string folder; std::getline(in, folder, ':');) {
      if (!folder.empty()) folders.emplace_back(folder);
    }
  }
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (!error) folders.push_back(self.parent_path().parent_path() / "lib" / "modelgen" / "models");
  return folders;
}

std::optional<ModelLibrary> prebuilt_model(const DescriptionToCompile& description) {
  for (const fs::path& folder : prebuilt_model_folders()) {
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
      if (entry.path().extension() != ".so") continue;
      try {
        ModelLibrary library =
            ModelLibrary::open(entry.path().string(), description.reference->description_sha256());
        if (disagreement(*library.identification_model(), *description.reference).empty()) {
          return library;
        }
      } catch (const ModelLibraryError&) {
        // Another description's model, or not a model at all: not this one.
      }
    }
  }
  return std::nullopt;
}

}  // namespace modelgen::internal
