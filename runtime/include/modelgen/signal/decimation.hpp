// Parallel decimation (Gautier & Briot eq. 13-14): the same zero-phase low-pass on every column,
// then one sample in n_d, so that decimating Y and every column of W keeps Y = W chi. A factor
// runs in stages of at most 10, as Matlab's decimate advises for its Chebyshev filter.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "modelgen/data/trajectory.hpp"
#include "modelgen/signal/lowpass.hpp"

namespace modelgen {

/// The largest factor of one decimation stage, as Matlab's decimate advises for its order-8
/// Chebyshev filter (whose poles crowd towards z = 1 as the factor grows). With the filter in
/// second-order sections as here, one stage of 100 or 1000 was measured as accurate as the
/// stages (white noise and in-band sines agree to 1e-3 away from the ends); the stages keep the
/// long filters off the full-rate samples and the design within the range it was checked for.
inline constexpr int kMaxStageFactor = 10;

/// The filter of one decimation stage of `factor`, as Matlab's decimate: Chebyshev type I,
/// order 8, 0.05 dB ripple, cut-off 0.8 (fs / 2) / factor, here with unit DC gain; frequencies
/// in cycles per sample (sample_rate_hz = 1). Throws std::invalid_argument for factor < 2.
LowPassFilter decimation_filter(int factor);

/// The stages decimate() runs for `factor`: factors of at most kMaxStageFactor whose product
/// is `factor`, as few as possible, largest first (the later, slower stages then filter fewer
/// samples); empty for factor 1. A factor with a prime factor above kMaxStageFactor (11, 13,
/// 22, 385, ...) cannot be staged: std::invalid_argument naming the prime and the nearest
/// factors that can (decimation_factor_below, and the next one above). Also for factor < 1.
std::vector<int> decimation_stages(int factor);

/// The largest factor <= `factor` that decimation_stages() accepts (its primes all <= 7), for
/// planning: 385 gives 384 = 8 x 8 x 6. At least 1.
int decimation_factor_below(int factor);

/// Rows decimate() keeps out of `rows`: rows 0, factor, 2 factor, ..., (rows - 1) / factor + 1
/// of them (0 for 0 rows).
Eigen::Index decimated_rows(Eigen::Index rows, int factor);

/// Parallel decimation (Gautier & Briot eq. 13-14): every column of `x` (samples x columns)
/// runs through the stages of decimation_stages(factor), each a zero-phase
/// decimation_filter(stage) (filtfilt edges) and one sample in `stage` kept; overall rows 0,
/// factor, 2 factor, ... of x come out into `out`, which must be
/// decimated_rows(x.rows(), factor) x x.cols(). The operation is linear and the same for every
/// column, so decimating Y and every column of W keeps Y = W chi (eq. 14). Factor 1 copies.
/// The first and last rows lean on the end samples (filtfilt's odd reflection keeps an end
/// sample's value, noise included): decimated_interior() says which rows are clear of them.
/// Allocates a few columns (x and out may have any strides: see StridedMatrixRef; an
/// expression that is not a view, e.g. a product, is evaluated into a temporary first). Throws
/// std::invalid_argument for factor < 1, a factor decimation_stages() refuses, a wrong `out`
/// shape, non-finite values.
void decimate(const ConstStridedMatrixRef& x, int factor, StridedMatrixRef out);

/// decimate() into a new decimated_rows(x.rows(), factor) x x.cols() matrix.
Eigen::MatrixXd decimate(const ConstStridedMatrixRef& x, int factor);

/// The rows of decimate()'s output that the end samples do not dominate: [first, first + count).
/// filtfilt's odd reflection pins each end of a column to its end sample, so the first and last
/// decimated rows carry that one sample's noise at full bandwidth (on closed-loop torques, where
/// the D term puts the encoder noise over the whole band, row 0 was measured 70 times noisier
/// than the rows in the middle). A row is dropped while the weight decimate() gives the end
/// sample exceeds the white-noise gain of a row in the middle (the root sum of squares of its
/// weights): the end sample alone would then bring more noise than all the others together.
/// Both computed by decimating unit impulses, so they hold for any data of `samples` rows.
/// Factor 1 keeps every row. Throws as decimation_stages() does.
struct DecimatedRange {
  Eigen::Index first = 0, count = 0;
};
DecimatedRange decimated_interior(Eigen::Index samples, int factor);

/// decimate() and then only the decimated_interior() rows.
Eigen::MatrixXd decimate_interior(const ConstStridedMatrixRef& x, int factor);

/// Decimates every column of q, dq, ddq and tau with the same zero-phase filter and keeps t at
/// the kept rows, the decimated_interior() ones (decimate_interior()): for comparing predicted
/// and measured torques in the frequency range and on the rows identify() fitted with the same
/// factor. (identify() itself decimates W and Y, eq. 13-14, not the positions.) Factor 1 leaves
/// x unchanged.
void decimate_trajectory(Trajectory& x, int factor);

}  // namespace modelgen
