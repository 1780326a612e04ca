// Digital low-pass filters designed by the bilinear transform (Butterworth, Chebyshev type I)
// and applied causally or without phase shift (forward and backward, as Matlab's filtfilt), on
// any strided view of a matrix.
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

namespace modelgen {

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

}  // namespace modelgen
