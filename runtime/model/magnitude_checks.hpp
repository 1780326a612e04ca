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
/// A body whose mass lies, on average, more than this many times its size from its centre of
/// mass is flagged; sizes below kMinimumBodySize count as that (a wrist link whose next joint
/// sits at its origin is still a body of some size). The published URDFs reach 5 (FloBaRoID's
/// CAD LWR 4 hand link, UR5 wrists 4.3); inertias written in g m^2 for kg m^2 multiply the
/// ratio by 32, in kg mm^2 by 1000.
inline constexpr double kPlausibleRadiusPerSize = 10;
inline constexpr double kMinimumBodySize = 0.1;  // m

/// A warning if a revolute position limit `value` (rad) is beyond one turn and reads as degrees
/// (a whole or half number, or no whole number of degrees nor multiple of pi/4 in radians:
/// 47.1238898, 15 pi, is a multi-turn wrist and passes); `what` names the joint and the field
/// ("joint 'j1': limit lower").
void check_angle_limit(const SourceLocation& where, const std::string& what, double value,
                       std::vector<DescriptionNote>& notes);
/// A warning if a revolute velocity limit `value` (rad/s) is above kPlausibleVelocity.
void check_velocity_limit(const SourceLocation& where, const std::string& what, double value,
                          std::vector<DescriptionNote>& notes);
/// A warning if a body of `mass` (kg) whose inertia about its centre of mass has the trace
/// `inertia_trace` (ixx + iyy + izz, kg m^2) spreads its mass too far for its `size` (m, the
/// distance from its frame to its farthest child joint or its centre of mass): the rms distance
/// of its mass from the centre, sqrt(trace / (2 mass)), above kPlausibleRadiusPerSize times
/// max(size, kMinimumBodySize). The note names the likely unit (g m^2, kg cm^2, kg mm^2).
/// Nothing for a massless body.
void check_inertia_size(const SourceLocation& where, const std::string& what, double mass,
                        double inertia_trace, double size, std::vector<DescriptionNote>& notes);
/// A warning if a mass `value` (kg) is above kPlausibleMass.
void check_mass(const SourceLocation& where, const std::string& what, double value,
                std::vector<DescriptionNote>& notes);

}  // namespace modelgen
