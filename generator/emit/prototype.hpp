// Prototypes of generated entry points: the documentation and signature of
// templates/functions/<name>.tmpl, and parameter lists built from the registry's arrays,
// wrapped to the 100-column generated style.
#pragma once

#include <string>
#include <vector>

#include "generator/emit/number_format.hpp"

namespace modelgen::gen {

/// The prototype of entry point `name` for `scalar` (templates/functions/<name>.tmpl), without
/// a final newline; without its leading comment when not `documented` (overloads after the
/// first share the first one's documentation).
std::string function_prototype(const std::string& name, Scalar scalar, bool documented);

/// "const double* q, const double* dq, double* W": `inputs` read-only, then `outputs`.
std::string parameter_list(const std::vector<std::string>& inputs,
                           const std::vector<std::string>& outputs, Scalar scalar);

/// `line` with its parameter list "(a, b, c)" broken after commas, greedily, so that no line is
/// longer than `width` where possible; continuation lines align after the '('.
std::string wrap_parameters(const std::string& line, std::size_t width);

}  // namespace modelgen::gen
