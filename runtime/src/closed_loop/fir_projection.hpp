// What the files of the projection method share (projection_method.cpp, fir_projection.cpp).
// Private to closed_loop/.
#pragma once

namespace modelgen::detail {

// A reference whose range is below this fraction of its size is held: its lags are the
// constant column again.
inline constexpr double kHeld = 1e-12;

}  // namespace modelgen::detail
