// Rounded quarter turns in descriptions: URDFs (and hand-written MDH tables) write pi/2 as
// 1.57075 or 1.5708 and pi as 3.14159. Taken literally those are tilts of 1e-6..1e-4 rad that
// break the robot's symmetries (an axis no longer parallel to gravity or to its neighbour) and
// make parameters "identifiable" that the real robot cannot identify. The loaders snap such
// values to the exact multiple of pi/2 and say so. Private to the description loaders.
#pragma once

#include <optional>
#include <string>

namespace modelgen {

/// Below this distance from k pi/2 a value is the double nearest to it (or a pi written with 15
/// digits, "1.5707963267949"): snapping it changes nothing worth a note.
inline constexpr double kSilentSnap = 1e-9;

/// The multiple k of pi/2 that `radians` is within `tolerance` of, if any (never with a
/// tolerance of 0: then every value is taken as written).
std::optional<long> nearest_quarter_turn(double radians, double tolerance);

/// k pi/2 as text: "0", "pi/2", "-pi", "3*pi/2".
std::string quarter_turn_text(long quarters);

/// "snapped to pi/2 (written 1.57075, 4.6e-05 rad off; --angle-tolerance 0.0001)", for notes.
std::string snap_note(const std::string& what, double written, long quarters, double tolerance);

}  // namespace modelgen
