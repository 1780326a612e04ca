// The registry of generated functions: every entry point of a generated model described once.
// The emitter loops over it; a new generated function is its builder
// (generator/functions/<name>.cpp), its template (templates/functions/<name>.tmpl), its entry
// here and its test.
#pragma once

#include <vector>

#include "generator/functions/function_entry.hpp"

namespace modelgen::gen {

/// Every generated function, in the order the builders run and the Model struct lists its
/// members. The generated files group the functions by Section (see there).
const std::vector<FunctionEntry>& function_registry();

}  // namespace modelgen::gen
