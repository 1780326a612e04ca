// Values a real robot could have but that more likely carry a unit slip (degrees for radians,
// grams for kilograms): warnings, never errors, named by file, line and field. Shared by the
// URDF and MDH YAML loaders. Private to the model core.
#pragma once

#include <string>
#include <vector>

#include "modelgen/model/error.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen {

/// Beyond these a value is flagged: a revolute limit more than one turn to either side (that
/// also reads as degrees), a revolute velocity limit above 50 rad/s (about 480 rpm at the
/// joint), a link above 10 t.
inline constexpr double kPlausibleAngle = 6.283185307179586;  // 2 pi rad
inline constexpr double kPlausibleVelocity = 50;              // rad/s
inline constexpr double kPlausibleMass = 10000;               // kg

/// A warning if a revolute position limit `value` (rad) is beyond one turn and reads as degrees
/// (a whole or half number, or no whole number of degrees nor multiple of pi/4 in radians:
/// 47.1238898, 15 pi, is a multi-turn wrist and passes); `what` names the joint and the field
/// ("joint 'j1': limit lower").
void check_angle_limit(const SourceLocation& where, const std::string& what, double value,
                       std::vector<DescriptionNote>& notes);
/// A warning if a revolute velocity limit `value` (rad/s) is above kPlausibleVelocity.
void check_velocity_limit(const SourceLocation& where, const std::string& what, double value,
                          std::vector<DescriptionNote>& notes);
/// A warning if a mass `value` (kg) is above kPlausibleMass.
void check_mass(const SourceLocation& where, const std::string& what, double value,
                std::vector<DescriptionNote>& notes);

}  // namespace modelgen
