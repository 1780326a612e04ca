// The generated source NAME.cpp: parameter names, drive-chain constants and the definitions of
// every entry point for each scalar type.
#pragma once

#include <string>

#include "generator/emit/render_input.hpp"

namespace modelgen::gen {

/// templates/model.cpp.tmpl filled for `in`.
std::string render_source(const RenderInput& in);

}  // namespace modelgen::gen
