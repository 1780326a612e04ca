// Magnitudes no robot reaches, per kind of data column: the data reader refuses a value beyond
// them as a unit, column or transmission slip, and simulate refuses to write one (a file it
// writes must read again).
#pragma once

#include <optional>
#include <string>

namespace modelgen::io {

struct PlausibleMagnitude {
  const char* kind;  ///< the column's prefix: "q", "qr", "dq", "ddq", "tau" or "i"
  double bound;      ///< the largest magnitude a robot gives, in `unit`
  const char* unit;  ///< "rad or m", "N m or N", ...
};

/// The bound of a data column named by its kind and joint number ("dq2", "tau1"); nothing for
/// a column without one ("t", or a name of no such form).
std::optional<PlausibleMagnitude> plausible_magnitude(const std::string& column);

}  // namespace modelgen::io
