// The generated header NAME.hpp: counts, parameter names, drive chain, the declarations of
// every entry point and the Model struct.
#pragma once

#include <string>

#include "generator/emit/render_input.hpp"

namespace modelgen::gen {

/// templates/model.hpp.tmpl filled for `in`.
std::string render_header(const RenderInput& in);

}  // namespace modelgen::gen
