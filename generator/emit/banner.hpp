// The opening comment of every generated C++ file: origin, regeneration command, input hash
// and the operation counts of every generated function.
#pragma once

#include <span>
#include <string>

#include "generator/emit/render_input.hpp"

namespace modelgen::gen {

/// The banner of the generated file `file` (templates/banner.tmpl), without a final newline,
/// with the operation counts of `functions`.
std::string render_banner(const std::string& file, const RenderInput& in,
                          std::span<const EmittedFunction> functions);

/// The banner with the operation counts of every generated function.
inline std::string render_banner(const std::string& file, const RenderInput& in) {
  return render_banner(file, in, in.functions);
}

}  // namespace modelgen::gen
