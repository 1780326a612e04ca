// Parallel decimation (Gautier & Briot eq. 13-14): the same zero-phase low-pass on every column,
// then one sample in n_d, so that decimating Y and every column of W keeps Y = W chi.
#pragma once

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/signal/lowpass.hpp"

namespace modelgen {

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

/// Decimates every column of q, dq, ddq and tau with the same zero-phase filter (decimate())
/// and keeps t at the kept rows: for comparing predicted and measured torques in the frequency
/// range identify() fitted with the same factor. (identify() itself decimates W and Y,
/// eq. 13-14, not the positions.) Factor 1 leaves x unchanged.
void decimate_trajectory(Trajectory& x, int factor);

}  // namespace modelgen
