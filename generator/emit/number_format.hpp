// Numeric literals in generated code: shortest round-trip text, always recognisably floating
// point, with the suffix of the target scalar type.
#pragma once

#include <string>

namespace modelgen::gen {

enum class Scalar { kDouble, kFloat };

/// "double" or "float".
const char* scalar_name(Scalar scalar);

/// Literal for `value` (finite): "0.225", "2.0", "1e-05", "-3.5"; for float the value is
/// rounded to float first and suffixed "f" ("0.225f").
std::string format_literal(double value, Scalar scalar);

}  // namespace modelgen::gen
