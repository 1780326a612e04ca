// The opening comment of every generated C++ file: origin, regeneration command, input hash
// and the operation counts of every generated function.
#pragma once

#include <string>

#include "generator/emit/render_input.hpp"

namespace modelgen::gen {

/// The banner of the generated file `file` (templates/banner.tmpl), without a final newline.
std::string render_banner(const std::string& file, const RenderInput& in);

}  // namespace modelgen::gen
