// Shortest round-trip formatting through std::to_chars, so each constant reads back as the
// exact double (or float) the derivation computed.

#include "generator/emit/number_format.hpp"

#include <charconv>
#include <cmath>
#include <string>
#include <stdexcept>

namespace modelgen::gen {

const char* scalar_name(Scalar scalar) { return scalar == Scalar::kFloat ? "float" : "double"; }

std::string format_literal(double value, Scalar scalar) {
  char buffer[64];
  std::to_chars_result result;
  if (scalar == Scalar::kFloat) {
    if (!std::isfinite(static_cast<float>(value))) {
      throw std::logic_error("format_literal: " + std::to_string(value) + " does not fit a float");
    }
    result = std::to_chars(buffer, buffer + sizeof buffer, static_cast<float>(value));
  } else {
    result = std::to_chars(buffer, buffer + sizeof buffer, value);
  }
  if (result.ec != std::errc()) throw std::logic_error("format_literal: cannot format");
  std::string text(buffer, result.ptr);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  if (scalar == Scalar::kFloat) text += "f";
  return text;
}

}  // namespace modelgen::gen
