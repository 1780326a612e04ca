// The generated sources: NAME.cpp with the parameter names and drive-chain constants, and one
// NAME_<function>.cpp per entry point with its definition for each scalar type.
#pragma once

#include <string>

#include "generator/emit/render_input.hpp"

namespace modelgen::gen {

/// templates/model.cpp.tmpl filled for `in`: the tables.
std::string render_source(const RenderInput& in);

/// templates/function.cpp.tmpl filled for one entry point of `in`.
std::string render_function_source(const RenderInput& in, const EmittedFunction& function);

}  // namespace modelgen::gen
