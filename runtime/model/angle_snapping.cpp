// Snapping of rounded quarter turns (see angle_snapping.hpp).

#include "runtime/model/angle_snapping.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "modelgen/model/number_text.hpp"

namespace modelgen {

std::optional<long> nearest_quarter_turn(double radians, double tolerance) {
  if (!(tolerance > 0) || !std::isfinite(radians)) return std::nullopt;
  const double quarters = std::round(radians / (std::numbers::pi / 2));
  if (std::abs(quarters) > 1e6) return std::nullopt;  // far beyond any joint angle written
  const double off = std::abs(radians - quarters * (std::numbers::pi / 2));
  if (off > tolerance) return std::nullopt;
  return static_cast<long>(quarters);
}

std::string quarter_turn_text(long quarters) {
  if (quarters == 0) return "0";
  const std::string sign = quarters < 0 ? "-" : "";
  const long k = std::labs(quarters);
  if (k % 2 == 0) return sign + (k == 2 ? "pi" : std::to_string(k / 2) + "*pi");
  return sign + (k == 1 ? "pi/2" : std::to_string(k) + "*pi/2");
}

std::string snap_note(const std::string& what, double written, long quarters, double tolerance) {
  const double off = std::abs(written - static_cast<double>(quarters) * (std::numbers::pi / 2));
  char offset[32];
  std::snprintf(offset, sizeof offset, "%.2g", off);
  return what + " " + shortest_text(written) + " taken as " + quarter_turn_text(quarters) +
         " (" + offset + " rad off, within --angle-tolerance " + shortest_text(tolerance) +
         "; give --angle-tolerance 0 to take it as written)";
}

}  // namespace modelgen
