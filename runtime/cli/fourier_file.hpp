// Fourier excitation trajectories for `modelid simulate`, read from YAML in either of the two
// conventions of the Swevers papers: velocity amplitudes (1997, FourierTrajectory's own:
// q = q0 + sum a/(l w) sin(l w t) - b/(l w) cos(l w t)) or position amplitudes (2002 eq. 15:
// q = q0 + sum a sin(l w t) + b cos(l w t), the form of its Table 1).
#pragma once

#include <string>

#include "modelgen/excitation.hpp"

namespace modelgen::internal {

/// Reads {period: S, form: velocity|position (default velocity), joints: [{q0: .., a: [..],
/// b: [..]} or {q0: .., terms: [{l: 25, a: .., b: ..}, ...]}, ...]} with one entry per joint:
/// dense lists give harmonics 1, 2, ..., sparse terms name theirs; the rest are zero.
/// Throws modelgen::InputError naming the file, line and column for a syntax error, a missing key,
/// an unknown form, a non-positive period or harmonic, a joint count that differs from `dof`.
FourierTrajectory read_fourier(const std::string& path, int dof);

}  // namespace modelgen::internal
