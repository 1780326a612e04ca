// Data preparation before identification. Periodic excitation (Swevers et al. 2002, section 4):
// period detection, averaging over whole periods with the noise variance of the averages, and
// re-estimation of the Fourier coefficients of eq. 15 so that dq and ddq come analytically from
// eq. 16-17. Non-periodic data (Gautier & Briot, section IV.A, eq. 13-14): zero-phase low-pass
// filtering of positions before central differences, and the parallel decimation of Y and of
// every column of W.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/data.hpp"
#include "modelgen/excitation.hpp"

namespace modelgen {

// ---------------------------------------------------------------------------------------------
// Sampling

/// The sample time of a uniformly sampled trajectory, dt = (t_last - t_first) / (samples - 1),
/// in s. Uniform means every sample lies within 1% of dt of the grid t_first + k dt.
/// Throws DataError naming the trajectory's source for fewer than 2 samples, a non-finite
/// time, or the first sample off the grid (its index, time and offset in samples).
double uniform_sample_time(const Trajectory& trajectory);

// ---------------------------------------------------------------------------------------------
// Periodic excitation (Swevers et al. 2002, eq. 15-17 and the variance formula after Figure 5)

/// The period of the positions, in s, from their autocorrelation: the Pearson correlation of
/// the record with itself shifted by a lag (all axes pooled, each weighted by its position
/// variance), computed by FFT for lags up to 3/4 of the record. Past the lobe around lag 0
/// (until the correlation first drops below 0.5), the period is the first lag whose
/// correlation peaks as high as the highest one (at least 0.9), refined to a fraction of a
/// sample by least-squares parabolas through the peaks at every multiple of the period in
/// range (over as few lags as the noise allows). Accuracy on simulated multi-sines: 3e-4
/// sample without noise, 0.01 with noise at 1% of the amplitude, 0.05 with 10%. An excitation
/// generated on the controller's sample clock has a whole number of samples per period;
/// rounding to it before average_periods avoids a misalignment error there when many periods
/// multiply a poor estimate.
/// Works on multi-sines whose fundamental is weak: only the true period brings every harmonic
/// of every axis back into phase. Needs uniform sampling and at least 2 recorded periods.
/// Throws DataError naming the source when the sampling is not uniform, fewer than 8 samples,
/// a value is not finite, the positions do not move, never decorrelate (a drift), never
/// correlate again above 0.9 (no period), or repeat with a period longer than half the record
/// (fewer than 2 periods; the message gives the period and its correlation).
double detect_period(const Trajectory& trajectory);

/// Several periods of a periodic experiment averaged into one (Swevers 2002, section 4).
struct PeriodicAverage {
  /// One period: t (the first N times of the record), q and tau averaged over the periods; dq
  /// and ddq averaged too when the record had them (has_velocity), else zero. N x dof.
  Trajectory averaged;
  /// Per axis, the variance of the noise on the averaged torque ((N m)^2) and position (rad^2):
  /// the sample variance over the periods divided by the number of periods (see
  /// average_periods).
  Eigen::VectorXd tau_noise_variance, q_noise_variance;
  int periods = 0;                      ///< P, the whole periods averaged
  Eigen::Index samples_per_period = 0;  ///< N = round(period / dt)
  double period = 0;                    ///< N dt, s
  Eigen::Index dropped_samples = 0;     ///< samples after the last whole period, not used
  double dropped_seconds = 0;           ///< dropped_samples * dt
};

/// Averages the P = floor(samples / N) whole periods of a uniformly sampled record, with
/// N = round(period / dt) samples per period; the tail after the last whole period is dropped
/// and reported. The noise variance of the averaged signal, per axis, is
///   sigma^2 = sum_k sum_j (x_j(k) - mean(k))^2 / (N (P - 1)) / P,
/// the unbiased per-sample variance over the periods divided by P. (The formula printed in the
/// paper divides by P (P N - 1) instead, which underestimates the variance by (P - 1) / P.)
/// Throws DataError naming the source for: non-uniform sampling, a period that is not positive
/// and finite, N < 2, a period that is not a whole number of samples (the misalignment it
/// causes over the P periods, |period / dt - N| P, exceeds 0.25 sample), fewer than 2 whole
/// periods, a non-finite q or tau.
PeriodicAverage average_periods(const Trajectory& trajectory, double period);

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

// ---------------------------------------------------------------------------------------------
// Low-pass filters (bilinear transform) and zero-phase filtering

/// A samples x columns view of doubles with any row and column strides: a matrix, a block of
/// one, or an Eigen::Map with Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic> over every n-th
/// row (one joint's rows of a regressor that interleaves the joints). Nothing is copied.
using StridedMatrixRef =
    Eigen::Ref<Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
using ConstStridedMatrixRef =
    Eigen::Ref<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;

/// A digital low-pass filter as a cascade of sections, each
///   H_s(z) = (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2)
/// (b2 = a2 = 0 for the first-order section of an odd order). Sections keep high orders and low
/// cut-offs numerically sound where one long polynomial would not. Every section has unit gain
/// at DC.
struct LowPassFilter {
  struct Section {
    double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;
  };
  std::vector<Section> sections;
  double sample_rate_hz = 1;
  double cutoff_hz = 0;  ///< the design cut-off (-3 dB Butterworth, ripple edge Chebyshev)
  int order = 0;

  /// H(exp(i 2 pi f / fs)) of one causal pass; f in Hz.
  std::complex<double> response(double frequency_hz) const;
};

/// Butterworth low-pass of any order >= 1 by the bilinear transform with the cut-off
/// pre-warped, so that |H| = 1 / sqrt(1 + (tan(pi f / fs) / tan(pi fc / fs))^(2 order)):
/// -3 dB at fc after one pass, -6 dB after filtfilt. Throws std::invalid_argument for an order
/// < 1, a sample rate <= 0, or a cut-off outside (0, fs / 2).
LowPassFilter butterworth_lowpass(int order, double cutoff_hz, double sample_rate_hz);

/// Chebyshev type I low-pass, pass-band ripple `ripple_db` up to fc, bilinear transform with
/// pre-warping: |H|^2 = g / (1 + eps^2 T_n(w)^2), w = tan(pi f / fs) / tan(pi fc / fs),
/// eps^2 = 10^(ripple_db / 10) - 1, with g set for unit gain at DC (Matlab's cheby1 instead
/// puts the ripple maximum at 1, which for an even order is -ripple_db at DC). Throws
/// std::invalid_argument as butterworth_lowpass does, and for ripple_db <= 0.
LowPassFilter chebyshev1_lowpass(int order, double ripple_db, double cutoff_hz,
                                 double sample_rate_hz);

/// One causal pass over every column of `x` (samples x columns), in place. The pass starts in
/// the steady state of the ramp through the first two samples, as if the input had always
/// been that ramp: a constant or linear column has no start-up transient.
void filter_causal(const LowPassFilter& filter, StridedMatrixRef x);

/// Zero-phase filtering of every column of `x` (samples x columns), in place: a forward then a
/// backward pass, so the overall response is |H|^2 with no phase shift (Matlab's filtfilt).
/// Edges: each column is extended at both ends by its odd reflection about the end sample
/// (2 x_0 - x_k: value and slope continue), over min(samples - 1, 10 time constants of the
/// filter's slowest pole) samples, and each pass starts in the steady state of the ramp
/// through its first two values (see filter_causal). Constants and ramps come out unchanged,
/// ends included; end effects come from the curvature of the signal at its ends only. Works
/// on one column at a time with one buffer of a padded column.
void filtfilt(const LowPassFilter& filter, StridedMatrixRef x);

/// Zero-phase low-pass of the positions (Butterworth of `order`, cut-off in Hz, filtfilt), then
/// dq and ddq by central differences (differentiate(): the first and last samples are
/// dropped); tau is kept as is for the parallel decimation. Gautier & Briot, section IV.A.
/// Throws DataError naming the source for non-uniform sampling, fewer than 3 samples, a cut-off
/// not in (0, fs / 2) (the message gives fs), non-finite positions.
void filter_positions(Trajectory& trajectory, double cutoff_hz, int order = 4);

// ---------------------------------------------------------------------------------------------
// Parallel decimation (Gautier & Briot eq. 13-14)

/// The filter decimate() applies for `factor`, as Matlab's decimate: Chebyshev type I, order 8,
/// 0.05 dB ripple, cut-off 0.8 (fs / 2) / factor, here with unit DC gain; frequencies in
/// cycles per sample (sample_rate_hz = 1). Throws std::invalid_argument for factor < 2.
LowPassFilter decimation_filter(int factor);

/// Rows decimate() keeps out of `rows`: rows 0, factor, 2 factor, ..., (rows - 1) / factor + 1
/// of them (0 for 0 rows).
Eigen::Index decimated_rows(Eigen::Index rows, int factor);

/// Parallel decimation (Gautier & Briot eq. 13-14): every column of `x` (samples x columns) is
/// low-passed with the same zero-phase decimation_filter(factor) (filtfilt edges) and one
/// sample in `factor` is kept, rows 0, factor, 2 factor, ... into `out`, which must be
/// decimated_rows(x.rows(), factor) x x.cols(). The operation is linear and the same for every
/// column, so decimating Y and every column of W keeps Y = W chi (eq. 14). Factor 1 copies.
/// Allocates one padded column (x and out may have any strides: see StridedMatrixRef; an
/// expression that is not a view, e.g. a product, is evaluated into a temporary first). Throws
/// std::invalid_argument for factor < 1, a wrong `out` shape, non-finite values.
void decimate(const ConstStridedMatrixRef& x, int factor, StridedMatrixRef out);

/// decimate() into a new decimated_rows(x.rows(), factor) x x.cols() matrix.
Eigen::MatrixXd decimate(const ConstStridedMatrixRef& x, int factor);

// ---------------------------------------------------------------------------------------------
// Choosing the cut-off and the decimation factor

/// The frequency (Hz) below which `energy_fraction` of the energy of the joint velocities lies,
/// all axes pooled: the excitation bandwidth for plan_filtering. Computed from the positions
/// (measured dq, often filtered by the drive, is not used): per axis q without its
/// least-squares line, Hann-windowed, power spectrum by FFT; the band above fs / 4 is taken as
/// white noise only, and 10 x its mean level (estimated from its median) is subtracted from
/// every line, so that sensor noise and encoder quantization, which differentiation would
/// amplify, do not count; the velocity spectrum is then (2 pi f)^2 times what is left.
/// Coloured errors (timing jitter, data resampled by interpolation) are not removed and raise
/// the estimate: check it, or give the bandwidth to plan_filtering directly.
/// Throws DataError naming the source for non-uniform sampling, fewer than 16 samples,
/// non-finite positions, positions that do not move above their noise; std::invalid_argument
/// for energy_fraction outside (0, 1).
double estimate_bandwidth(const Trajectory& trajectory, double energy_fraction = 0.99);

/// Filtering and decimation settings for non-periodic data. Plain values: a caller may
/// override any of them (e.g. from the command line) before use.
struct FilterPlan {
  double sample_rate_hz = 0;
  double bandwidth_hz = 0;        ///< excitation bandwidth the plan was made for
  double position_cutoff_hz = 0;  ///< filter_positions cut-off
  int position_order = 4;         ///< filter_positions Butterworth order
  int decimation_factor = 1;      ///< n_d of decimate
  /// 0.8 (fs / 2) / n_d, the decimation filter's cut-off (no filter is applied for n_d = 1)
  double decimation_cutoff_hz = 0;
  std::string explanation;  ///< one line saying what was chosen and why
};

/// Gautier's practice, as a rule: the position filter must not touch the dynamics, so its
/// cut-off is 10 x the bandwidth (at most 0.8 x Nyquist); the decimation keeps the identified
/// frequency range, so n_d is the largest factor whose decimation filter cut-off,
/// 0.8 (fs / 2) / n_d, is still at least 2 x the bandwidth (n_d = 1 when none is).
/// Throws std::invalid_argument for a sample rate <= 0 or a bandwidth not in (0, fs / 2).
FilterPlan plan_filtering(double sample_rate_hz, double bandwidth_hz);

}  // namespace modelgen
