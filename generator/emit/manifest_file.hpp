// The manifest NAME.json written beside the generated sources: the same facts as the banners
// (generator, input, hash, operation counts) plus the parameters and regrouping relations, as
// data.
#pragma once

#include <string>

#include "generator/emit/render_input.hpp"

namespace modelgen::gen {

/// The manifest of `in` as JSON text, ending with a newline.
std::string render_manifest(const RenderInput& in);

}  // namespace modelgen::gen
