// The generated models of the shipped robots compiled into modelid, found by robot name.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "modelgen/model.hpp"

namespace modelgen::internal {

/// The compiled-in model named `name` ("tx40", "kr150", ...), or nullptr.
std::unique_ptr<IdentificationModel> make_shipped_model(const std::string& name);

/// Names of the compiled-in models, sorted.
std::vector<std::string> shipped_model_names();

}  // namespace modelgen::internal
