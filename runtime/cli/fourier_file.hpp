// Fourier excitation trajectories for `modelid simulate`, read from YAML (Swevers 2002,
// eq. 15: q_j(t) = q0_j + sum_l a_jl sin(l w t) + b_jl cos(l w t)).
#pragma once

#include <string>

#include "modelgen/excitation.hpp"

namespace modelgen::internal {

/// Reads {period: S, joints: [{q0: .., a: [..], b: [..]}, ...]} with one entry per joint and
/// the same number of harmonics in every a and b. Throws gen::InputError naming the file,
/// line and column for a syntax error, a missing key, a non-positive period or a joint count
/// that differs from `dof`.
FourierTrajectory read_fourier(const std::string& path, int dof);

}  // namespace modelgen::internal
