// Numbers as modelid prints them: shortest round-trip text for files, fixed-width significant
// digits for tables on screen.
#pragma once

#include <string>

namespace modelgen::internal {

/// The shortest text that reads back as exactly `value` (std::to_chars), for CSV and JSON.
std::string shortest(double value);

/// `value` with `precision` significant digits right-aligned in `width` characters (printf
/// %*.*g); "inf"/"nan" spelled as printf does.
std::string fixed(double value, int width, int precision);

/// `text` padded with spaces on the right to `width` characters (longer text is kept whole).
std::string pad(std::string text, std::size_t width);

}  // namespace modelgen::internal
