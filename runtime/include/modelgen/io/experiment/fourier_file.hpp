// Fourier excitation trajectories for `modelid simulate`, read from YAML in either of the two
// conventions of the Swevers papers: velocity amplitudes (1997, FourierTrajectory's own:
// q = q0 + sum a/(l w) sin(l w t) - b/(l w) cos(l w t)) or position amplitudes (2002 eq. 15:
// q = q0 + sum a sin(l w t) + b cos(l w t), the form of its Table 1).
#pragma once

#include <string>

#include "modelgen/excitation/fourier_trajectory.hpp"

namespace modelgen::io {

/// Hard limits of a trajectory file: a period from a millisecond to about eleven days, and
/// harmonics up to 1000 (the papers use up to 25); beyond them a typo would make simulate
/// allocate or compute for hours.
constexpr double kMinFourierPeriod = 1e-3;
constexpr double kMaxFourierPeriod = 1e6;
constexpr long kMaxFourierHarmonic = 1000;

/// Reads {period: S, form: velocity|position (default velocity), joints: [{q0: .., a: [..],
/// b: [..]} or {q0: .., terms: [{l: 25, a: .., b: ..}, ...]}, ...]} with one entry per joint:
/// dense lists give harmonics 1, 2, ..., sparse terms name theirs; the rest are zero.
/// Throws modelgen::InputError naming the file, line and column for a syntax error, a missing,
/// unknown or repeated key, an unknown form, a number that is not finite, a period or harmonic
/// outside the limits above, a harmonic given twice, a joint count that differs from `dof`.
FourierTrajectory read_fourier(const std::string& path, int dof);

}  // namespace modelgen::io
