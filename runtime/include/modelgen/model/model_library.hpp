// A generated model loaded at run time: the shared library compiled from the output of `modelgen
// ROBOT -o DIR --loadable` (docs/generated-code.md), opened with dlopen, its table
// (modelgen/model/loadable_model.h) checked against this runtime and the description before
// anything in it is used, and adapted to IdentificationModel. The drive model on the same
// library is modelgen/ml/loaded_drive_model.hpp.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "modelgen/model/error.hpp"
#include "modelgen/model/identification_model.hpp"
#include "modelgen/model/loadable_model.h"

namespace modelgen {

/// A shared library that cannot serve as the generated model asked for: missing, not a shared
/// library, without the entry point, or with a table another runtime or another description
/// made. what() reads "PATH: error: MESSAGE"; where().file is PATH.
class ModelLibraryError : public Error {
 public:
  ModelLibraryError(const std::string& path, const std::string& message);
};

/// A loaded and checked model library. Copies share the loaded library, and so does every model
/// made from it: the library stays loaded (dlclose) until the last of them is gone.
class ModelLibrary {
 public:
  /// Loads `path` (dlopen, every symbol resolved now; a path without '/' names a file in the
  /// working directory, not one on the library search path), finds MODELGEN_LOADABLE_SYMBOL
  /// and checks its table in this order: ABI version and struct size (of loadable_model.h),
  /// generated format version (kGeneratedFormatVersion), the description's SHA-256 against
  /// `description_sha256` (64 hex digits, of the description the caller uses), then sizes (dof
  /// 1 to 32, positive counts, base parameters at most the standard ones, drive-regressor
  /// entries increasing places of the dof x drive_params regressor) and that no pointer is null.
  /// Throws ModelLibraryError naming `path` and what differs.
  static ModelLibrary open(const std::string& path, const std::string& description_sha256);

  const std::string& path() const { return path_; }
  /// The checked table; valid while this library is.
  const modelgen_loadable_table& table() const { return *table_; }

  /// The identification model on the library's functions (as GeneratedModel on compiled-in
  /// code: every output entry written, those the generated code leaves to the caller zeroed
  /// first). It keeps the library loaded.
  std::unique_ptr<IdentificationModel> identification_model() const;

 private:
  ModelLibrary(std::shared_ptr<void> handle, const modelgen_loadable_table* table, std::string path)
      : handle_(std::move(handle)), table_(table), path_(std::move(path)) {}

  std::shared_ptr<void> handle_;  // the dlopen handle; dlclose when the last copy goes
  const modelgen_loadable_table* table_;
  std::string path_;
};

}  // namespace modelgen
