// How much of a signal's power lies above a frequency: the check that a fit's residual is
// where the preparation said the excitation is.
#pragma once

#include <Eigen/Core>

namespace modelgen {

/// The power of the columns of `x` (samples x columns, uniformly sampled every `dt` s) above
/// `frequency_hz`, summed over the columns: per column, mean removed, Hann window, power
/// spectrum by FFT, the lines above the frequency summed. In the units of x squared times a
/// scale common to every x of the same length, so only ratios between signals of the same
/// length are meaningful. 0 for fewer than 4 samples or a frequency at or above Nyquist.
double power_above(const Eigen::MatrixXd& x, double dt, double frequency_hz);

}  // namespace modelgen
