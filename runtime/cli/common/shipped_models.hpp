// The generated models of the shipped robots compiled into modelid, found by robot name.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "modelgen/ml/drive_model.hpp"
#include "modelgen/model/identification_model.hpp"

namespace modelgen::internal {

/// The compiled-in model named `name` ("tx40", "kr150", ...), or nullptr.
std::unique_ptr<IdentificationModel> make_shipped_model(const std::string& name);

/// The generated drive model (Swevers eq. 12 with its analytic Jacobians) of the compiled-in
/// model generated from a description with SHA-256 `description_sha256`, or nullptr; `name`,
/// when not null, receives that model's name.
std::unique_ptr<DriveModel> make_shipped_drive_model(const std::string& description_sha256,
                                                     std::string* name = nullptr);

/// The description file the compiled-in model `name` was generated from, in the source tree
/// modelid was built from, when that file is there and is still the same (same SHA-256): its
/// joint limits and names are not compiled in. Empty otherwise (an installed modelid without
/// its sources, an edited description).
std::string shipped_description_path(const std::string& name);

/// Names of the compiled-in models, sorted.
std::vector<std::string> shipped_model_names();

}  // namespace modelgen::internal
