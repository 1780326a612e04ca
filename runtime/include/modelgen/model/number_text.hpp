// Numbers as text wherever modelgen writes them for a program or a person to read back (CSV,
// JSON, messages, generated literals): the shortest decimal that reads back as the same value.
#pragma once

#include <string>

namespace modelgen {

/// The shortest text that reads back as exactly `value` (std::to_chars): "0.225", "1e-05",
/// "-3", "inf", "nan".
std::string shortest_text(double value);
/// The same for a float: the shortest text that reads back as that float ("0.1" for 0.1f).
std::string shortest_text(float value);

}  // namespace modelgen
