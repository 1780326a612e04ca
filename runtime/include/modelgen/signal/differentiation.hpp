// Velocities and accelerations from measured positions: central differences, either of the
// positions as they are or after a zero-phase low-pass (Gautier & Briot, section IV.A).
#pragma once

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"

namespace modelgen {

/// Fills dq and ddq from q by central differences (second order, unequal steps allowed) and
/// drops the first and last samples, where central differences do not exist. Used when the
/// file has no dq/ddq columns. Throws DataError naming the source for fewer than 3 samples.
void differentiate(Trajectory& trajectory);

/// Zero-phase low-pass of the positions (Butterworth of `order`, cut-off in Hz, filtfilt of
/// modelgen/signal/lowpass.hpp), then dq and ddq by central differences (differentiate(): the
/// first and last samples are dropped); tau is kept as is for the parallel decimation.
/// Gautier & Briot, section IV.A.
/// Throws DataError naming the source for non-uniform sampling, fewer than 3 samples, a cut-off
/// not in (0, fs / 2) (the message gives fs), non-finite positions.
void filter_positions(Trajectory& trajectory, double cutoff_hz, int order = 4);

}  // namespace modelgen
