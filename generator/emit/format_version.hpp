// The version of the generated interface, written into every generated header and manifest.
#pragma once

namespace modelgen::gen {

/// Format of the generated interface; bump when the generated API changes incompatibly.
inline constexpr int kFormatVersion = 3;

}  // namespace modelgen::gen
