// The sample time of a trajectory, and resampling on a uniform grid: every digital filter of
// data preparation assumes a uniform sample time.
#pragma once

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"

namespace modelgen {

/// The sample time of a uniformly sampled trajectory, dt = (t_last - t_first) / (samples - 1),
/// in s. Uniform means every sample lies within 1% of dt of the grid t_first + k dt.
/// Throws DataError naming the trajectory's source for fewer than 2 samples, a non-finite
/// time, or the first sample off the grid (its index, time and offset in samples).
double uniform_sample_time(const Trajectory& trajectory);

/// Linear interpolation of q, tau (and dq, ddq when present) on t0, t0 + dt, ... up to the last
/// time. Throws DataError naming the source for dt <= 0, fewer than 2 samples, or a grid of
/// more than 100 points per sample (holes in the time stamps; it would be mostly invented).
Trajectory resample_uniform(const Trajectory& x, double dt);

}  // namespace modelgen
