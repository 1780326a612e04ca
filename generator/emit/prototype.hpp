// Prototypes of generated entry points: the documentation of templates/functions/<name>.tmpl
// and a parameter list built from the registry's arrays (sin_q, cos_q after q in a _sincos
// variant), wrapped to the 100-column generated style.
#pragma once

#include <string>
#include <vector>

#include "generator/emit/function_emitter.hpp"
#include "generator/emit/number_format.hpp"

namespace modelgen::gen {

/// The prototype of `function` for `scalar` (templates/prototype.tmpl), without a final newline:
/// its documentation when `documented` (templates/functions/<name>.tmpl, or
/// templates/sincos_variant.tmpl for a _sincos variant; overloads after the first share the
/// first one's), then `void name(parameters)` with the parameter list wrapped.
std::string function_prototype(const EmittedFunction& function, Scalar scalar, bool documented);

/// "const double* q, const double* dq, double* W": `inputs` read-only, then `outputs`.
std::string parameter_list(const std::vector<std::string>& inputs,
                           const std::vector<std::string>& outputs, Scalar scalar);

/// `line` with its parameter list "(a, b, c)" broken after commas, greedily, so that no line is
/// longer than `width` where possible; continuation lines align after the '('.
std::string wrap_parameters(const std::string& line, std::size_t width);

}  // namespace modelgen::gen
