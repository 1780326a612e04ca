// Re-estimation of the Fourier series of a periodic excitation from one averaged period
// (Swevers et al. 2002, eq. 15 and section 4), so that dq and ddq come analytically from
// eq. 16-17.
#pragma once

#include "modelgen/data/data_error.hpp"
#include "modelgen/data/trajectory.hpp"
#include "modelgen/excitation/fourier_trajectory.hpp"
#include "modelgen/signal/period.hpp"

namespace modelgen {

/// The default number of harmonics to re-estimate from an averaged period: the highest
/// harmonic l (over all axes) whose amplitude |c_jl| in the positions stands out of the noise,
/// |c_jl| > max(6 sqrt(2 q_noise_variance_j / N), 1e-9 max_jl |c_jl|). Under noise alone a
/// line passes with probability exp(-18) = 1.5e-8, so noise lines are not kept but the
/// harmonics of the excitation and of the tracking error are (Swevers 2002: "more harmonics can
/// be considered ... depending on the frequency contents of the tracking error"). At least 1,
/// at most the largest count fit_fourier accepts, (N - 1) / 2.
int select_harmonics(const PeriodicAverage& average);

/// Re-estimates q0, a and b of eq. 15 for every axis from one period of averaged positions by
/// the discrete Fourier transform (Swevers 2002, section 4): the N samples of `one_period` must
/// be uniform and span `period` (N dt = period within 5% of dt: pass PeriodicAverage::period);
/// times need not start at 0. Harmonics 1..`harmonics` are kept, the rest of the spectrum
/// (noise) is dropped; select_harmonics gives a default count.
/// Throws DataError naming the source for: non-uniform sampling, N dt != period, harmonics < 1
/// or 2 harmonics >= N (the Nyquist limit), non-finite positions.
FourierTrajectory fit_fourier(const Trajectory& one_period, double period, int harmonics);

/// Replaces q, dq and ddq by the analytic eq. 15-17 values of `fourier` at the trajectory's
/// times; sets has_velocity. Throws DataError naming the source when `fourier` has not one row
/// per axis of the trajectory.
void apply_fourier(Trajectory& trajectory, const FourierTrajectory& fourier);

}  // namespace modelgen
