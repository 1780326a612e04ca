// A Fourier excitation (Swevers eq. 15-17) on the uniform grid t_s = period s / n of one period,
// evaluated by blocks with inverse FFTs instead of point by point: the grid is cut into
// p = n / m interleaved blocks s = r + p k (k = 0..m-1); on block r the series is a
// trigonometric polynomial in k of period m, so folding harmonic l onto bin l mod m and one
// inverse FFT of size m give its m values. The cost is O(n log m + n L / m) for L harmonics,
// against O(n L) point by point; the limit grid has n >= 1000 L points and blocks of m >= L.
#pragma once

#include <functional>
#include <limits>

#include <Eigen/Core>

#include "modelgen/excitation/fourier_trajectory.hpp"

namespace modelgen::detail {

/// The largest block the grid is cut into.
constexpr long kMaxGridBlock = 8192;

/// The largest divisor of `n` (>= 1) at most kMaxGridBlock whose prime factors are 2, 3 and 5,
/// the radices of Eigen's FFT: the block size m of a grid of n points.
long grid_block(long n);

/// One block of the grid: the points s = first + stride k, k = 0..rows-1, and q, dq, ddq
/// there, one row per point and one column per joint.
struct GridBlock {
  long first = 0, stride = 1;
  Eigen::MatrixXd q, dq, ddq;
  long index(Eigen::Index k) const { return first + stride * static_cast<long>(k); }
};

/// Calls `visit` once per block of the `n`-point grid of one period of `trajectory` (n >= 1),
/// every point in exactly one block. The values equal FourierTrajectory::evaluate at
/// t = period s / n to the FFT's rounding (a few 1e-16 of the sum of the terms' amplitudes).
void for_each_grid_block(const FourierTrajectory& trajectory, long n,
                         const std::function<void(const GridBlock&)>& visit);

/// Bounds of |q - q0|, |dq| and |ddq| of each joint: the sums of the terms' amplitudes, the
/// scale of the grid evaluation's rounding.
struct SeriesBounds {
  Eigen::VectorXd q, dq, ddq;
};
SeriesBounds series_bounds(const FourierTrajectory& trajectory);

/// The largest value offered and the first grid point that reaches it, values within
/// `tolerance` of each other being equal: rounding must not choose between the equal peaks of
/// a periodic signal (|dq| of one harmonic peaks 2 l times a period), the first one is kept.
struct GridPeak {
  double value = -std::numeric_limits<double>::infinity();
  long index = -1;
  void offer(double v, long s, double tolerance) {
    if (index < 0 || v > value + tolerance) {
      value = v;
      index = s;
    } else if (v >= value - tolerance && s < index) {
      value = v > value ? v : value;
      index = s;
    }
  }
};

}  // namespace modelgen::detail
