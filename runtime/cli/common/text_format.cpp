// Number and column formatting shared by the modelid commands.

#include "runtime/cli/common/text_format.hpp"

#include "modelgen/model/number_text.hpp"

#include <cstdio>

namespace modelgen::internal {

std::string shortest(double value) { return shortest_text(value); }

std::string fixed(double value, int width, int precision) {
  char text[64];
  std::snprintf(text, sizeof text, "%*.*g", width, precision, value);
  return text;
}

std::string pad(std::string text, std::size_t width) {
  if (text.size() < width) text.resize(width, ' ');
  return text;
}

}  // namespace modelgen::internal
