// Shortest round-trip formatting through std::to_chars, so each constant reads back as the
// exact double (or float) the derivation computed.

#include "generator/emit/number_format.hpp"

#include <cmath>
#include <string>
#include <stdexcept>

#include "modelgen/model/number_text.hpp"

namespace modelgen::gen {

const char* scalar_name(Scalar scalar) { return scalar == Scalar::kFloat ? "float" : "double"; }

std::string format_literal(double value, Scalar scalar) {
  if (scalar == Scalar::kFloat && !std::isfinite(static_cast<float>(value))) {
    throw std::logic_error("format_literal: " + std::to_string(value) + " does not fit a float");
  }
  std::string text = scalar == Scalar::kFloat ? shortest_text(static_cast<float>(value))
                                              : shortest_text(value);
  if (text.empty()) throw std::logic_error("format_literal: cannot format");
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  if (scalar == Scalar::kFloat) text += "f";
  return text;
}

}  // namespace modelgen::gen
