// Power above a frequency by a windowed FFT (ratios of such powers are what callers compare).

#include "modelgen/signal/band_power.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "runtime/src/signal/dft.hpp"

namespace modelgen {

double power_above(const Eigen::MatrixXd& x, double dt, double frequency_hz) {
  const Eigen::Index n = x.rows();
  if (n < 4 || !(dt > 0) || !(frequency_hz * 2 * dt < 1)) return 0;
  const Eigen::Index fft_size = detail::next_power_of_two(n), half = fft_size / 2;
  const Eigen::Index first = std::max<Eigen::Index>(
      1, static_cast<Eigen::Index>(std::ceil(frequency_hz * dt * static_cast<double>(fft_size))));
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> windowed(fft_size), spectrum;
  double power = 0;
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const double mean = x.col(j).mean();
    std::fill(windowed.begin(), windowed.end(), 0.0);
    for (Eigen::Index s = 0; s < n; ++s) {
      const double hann =
          0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(s) / (n - 1));
      windowed[s] = hann * (x(s, j) - mean);
    }
    fft.fwd(spectrum, windowed);
    for (Eigen::Index l = first; l <= half; ++l) power += std::norm(spectrum[l]);
  }
  return power;
}

}  // namespace modelgen
