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
/// harmonic l (over all axes) whose line in the averaged positions stands out of the noise at
/// that line, |X_jl|^2 > 25 v_jl, v_jl the noise variance of the line (q_line_variance)
/// averaged over lines l - 2..l + 2 (one line's variance from P periods has only 2 (P - 1)
/// degrees of freedom), the largest such mean within 2 lines (a narrow peak of noise is not
/// averaged away), and above round-off (1e-18 of the largest line power). Under noise alone
/// |X|^2 / v is about exponential: a line passes with probability near exp(-25) = 1.4e-11. The harmonics of the excitation and of the tracking error
/// are kept (Swevers 2002: "more harmonics can be considered ... depending on the frequency
/// contents of the tracking error"), a coloured noise is not: a closed loop's response to its
/// encoder noise lifts the positions' noise around the loop's bandwidth far above their mean
/// noise level, and a threshold from that mean (the per-axis q_noise_variance, as before) took
/// 87 harmonics of a 5-harmonic excitation for signal on the closed-loop TX-40 test. Without
/// line variances (an average made elsewhere), the per-axis ones are used as white.
/// At least 1, at most the largest count fit_fourier accepts, (N - 1) / 2.
int select_harmonics(const PeriodicAverage& average);

/// The harmonics of the averaged torques to keep (Bona & Curatella section 3.4: the torque
/// estimate keeps the lines up to the excitation's band, the controller's content above it is
/// noise): the highest harmonic whose torque line stands out of its noise as select_harmonics
/// tests the positions (tau_line_variance), at least `position_harmonics` (the regressor
/// reaches above the positions' band, the dynamics being nonlinear in them).
int select_torque_harmonics(const PeriodicAverage& average, int position_harmonics);

/// Keeps harmonics 0..`harmonics` of every column of `one_period` (one period, N rows) and
/// drops the rest: a Fourier projection, the periodic low-pass. Throws DataError naming the
/// source for harmonics < 0 or 2 harmonics >= N.
void keep_harmonics(Trajectory& one_period, Eigen::MatrixXd& columns, int harmonics);

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
