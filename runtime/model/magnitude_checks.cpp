// Plausibility of magnitudes in robot descriptions: a URDF written in degrees or a mass in
// grams loads without error and gives nonsense downstream (a design that spins a joint 128 rad,
// torques a thousand times too large), so such values are named with the likely slip.

#include "runtime/model/magnitude_checks.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "modelgen/model/number_text.hpp"

namespace modelgen {

void check_angle_limit(const SourceLocation& where, const std::string& what, double value,
                       std::vector<DescriptionNote>& notes) {
  // Files write 2 pi rounded (UR: 6.28318530718, a little above): a slack of 1e-4 rad.
  if (std::abs(value) <= kPlausibleAngle + 1e-4) return;
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

void check_mass(const SourceLocation& where, const std::string& what, double value,
                std::vector<DescriptionNote>& notes) {
  if (value <= kPlausibleMass) return;
  notes.push_back({where,
                   what + " is " + shortest_text(value) + " kg, above " +
                       shortest_text(kPlausibleMass) + " kg; masses are in kg: grams?",
                   true});
}

}  // namespace modelgen
