// Shortest round-trip formatting through std::to_chars (no locale, no precision to choose).

#include "modelgen/model/number_text.hpp"

#include <charconv>

namespace modelgen {

namespace {

template <class T>
std::string shortest(T value) {
  char buffer[64];  // the longest double ("-2.2250738585072014e-308") is 24 characters
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc() ? std::string(buffer, end) : std::string();
}

}  // namespace

std::string shortest_text(double value) { return shortest(value); }
std::string shortest_text(float value) { return shortest(value); }

}  // namespace modelgen
