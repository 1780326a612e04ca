// The discrete Fourier transform of any length, for period detection and Fourier re-estimation.
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

namespace modelgen::detail {

/// The smallest power of two >= n (1 for n <= 1).
Eigen::Index next_power_of_two(Eigen::Index n);

/// X_l = sum_k x_k exp(-2 pi i l k / n), l = 0..n-1, in O(n log n) for any n (Bluestein's
/// chirp for lengths that are not powers of two).
std::vector<std::complex<double>> dft(const Eigen::Ref<const Eigen::VectorXd>& x);

}  // namespace modelgen::detail
