// Plausibility of magnitudes in robot descriptions: a URDF written in degrees or a mass in
// grams loads without error and gives nonsense downstream (a design that spins a joint 128 rad,
// torques a thousand times too large), so such values are named with the likely slip.

#include "runtime/model/magnitude_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "modelgen/model/number_text.hpp"

namespace modelgen {

namespace {

// Whether a revolute limit beyond one turn reads as a value in degrees rather than a multi-turn
// joint in radians. A human writes degrees as a whole or half number (128, 170.5); a multi-turn
// limit in radians is a converted whole number of degrees (6.10865238198 is 350 degrees, the
// COMAU wrist's 47.1238898 is 2700 degrees to 1e-7 rad) or a multiple of pi/4 written to two
// decimals (4.71, 12.57). Anything else beyond one turn (10.3) is not a usual radian value either.
// A computed value for a message: three significant digits ("0.426", "1.2e+03").
std::string three_digits(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

bool reads_as_degrees(double value) {
  constexpr double kPi = std::numbers::pi;
  const double magnitude = std::abs(value);
  if (std::abs(2 * magnitude - std::round(2 * magnitude)) < 1e-9) return true;
  const double degrees = magnitude * 180 / kPi;
  if (std::abs(degrees - std::round(degrees)) < 1e-3) return false;
  const double quarter_turns = magnitude / (kPi / 4);
  if (std::abs(quarter_turns - std::round(quarter_turns)) * (kPi / 4) < 0.005) return false;
  return true;
}

}  // namespace

void check_angle_limit(const SourceLocation& where, const std::string& what, double value,
                       std::vector<DescriptionNote>& notes) {
  // Files write 2 pi rounded (UR: 6.28318530718, a little above): a slack of 1e-4 rad.
  if (std::abs(value) <= kPlausibleAngle + 1e-4 || !reads_as_degrees(value)) return;
  notes.push_back({where,
                   what + " is " + shortest_text(value) +
                       " rad, more than one turn (2 pi) to that side; limits are in radians: "
                       "degrees?",
                   true});
}

void check_velocity_limit(const SourceLocation& where, const std::string& what, double value,
                          std::vector<DescriptionNote>& notes) {
  if (value <= kPlausibleVelocity) return;
  notes.push_back({where,
                   what + " is " + shortest_text(value) + " rad/s, above " +
                       shortest_text(kPlausibleVelocity) +
                       " rad/s; velocity limits are in rad/s: degrees per second?",
                   true});
}

// sum_i I_ii = integral of 2 |r|^2 dm about the centre of mass, so sqrt(trace / (2 m)) is the
// rms distance of the mass from its centre: it cannot much exceed the body's extent.
void check_inertia_size(const SourceLocation& where, const std::string& what, double mass,
                        double inertia_trace, double size, std::vector<DescriptionNote>& notes) {
  if (!(mass > 0)) return;
  const double radius = std::sqrt(inertia_trace / (2 * mass));
  const double extent = std::max(size, kMinimumBodySize);
  if (radius <= kPlausibleRadiusPerSize * extent) return;
  // The units that bring the radius within what published links have (0.05 to 5 times the
  // size), else the one that comes nearest.
  struct Slip {
    double factor;
    const char* unit;
  };
  const Slip slips[] = {{1e3, "g m^2"}, {1e4, "kg cm^2"}, {1e6, "kg mm^2"}};
  std::string units;
  double nearest = 1e300;
  const char* nearest_unit = slips[0].unit;
  for (const Slip& slip : slips) {
    const double ratio = radius / std::sqrt(slip.factor) / extent;
    if (ratio >= 0.05 && ratio <= 5)
      units += (units.empty() ? "" : " or ") + std::string(slip.unit);
    if (std::abs(std::log(ratio)) < nearest) {
      nearest = std::abs(std::log(ratio));
      nearest_unit = slip.unit;
    }
  }
  if (units.empty()) units = nearest_unit;
  notes.push_back(
      {where,
       what + ": moments of inertia about the centre of mass summing to " +
           three_digits(inertia_trace) + " kg m^2 for a mass of " + shortest_text(mass) +
           " kg put its mass " + three_digits(radius) + " m from its centre (rms), more than " +
           shortest_text(kPlausibleRadiusPerSize) + " times the link's size of " +
           three_digits(extent) + " m (its farthest child joint or centre of mass, at least " +
           shortest_text(kMinimumBodySize) + " m); inertias are in kg m^2: " + units + "?",
       true});
}

void check_mass(const SourceLocation& where, const std::string& what, double value,
                std::vector<DescriptionNote>& notes) {
  if (value <= kPlausibleMass) return;
  notes.push_back({where,
                   what + " is " + shortest_text(value) + " kg, above " +
                       shortest_text(kPlausibleMass) + " kg; masses are in kg: grams?",
                   true});
}

}  // namespace modelgen
