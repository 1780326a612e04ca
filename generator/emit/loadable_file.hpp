// STEM_loadable.cpp of `modelgen --loadable`: the C entry point returning the table of a model
// built as a shared library, which the runtime loads and checks (modelgen/model/model_library.hpp,
// the layout in modelgen/model/loadable_model.h).
#pragma once

#include <string>
#include <vector>

#include "generator/emit/render_input.hpp"

namespace modelgen::gen {

/// The entry points the table points to (the double ones the runtime's adapters call): what
/// --loadable needs generated.
const std::vector<std::string>& loadable_functions();

/// templates/loadable.cpp.tmpl filled for `in`.
std::string render_loadable_source(const RenderInput& in);

/// The generated files a shared library of the model compiles, in file order: STEM.cpp, the
/// function files of loadable_functions() and of the entry points they call, STEM_loadable.cpp.
/// The other function files are not needed (the manifest's "loadable_sources").
std::vector<std::string> loadable_sources(const RenderInput& in);

}  // namespace modelgen::gen
