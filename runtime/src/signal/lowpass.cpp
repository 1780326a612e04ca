// Butterworth and Chebyshev I low-pass design by the bilinear transform, and causal and
// zero-phase filtering with the cascade of filter_sections.

#include "modelgen/signal/lowpass.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/src/signal/filter_sections.hpp"
#include "runtime/src/signal/trajectory_checks.hpp"

namespace modelgen {

namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;
using detail::filtfilt_column;
using detail::format;
using detail::run_sections;
using detail::settling_samples;

// Digital sections from the analog prototype poles normalised to a cut-off of 1 rad/s (one
// pole of each conjugate pair, Im > 0, and the real poles). Bilinear transform with the cut-off
// pre-warped: s / wc = (z - 1) / (K (z + 1)), K = tan(pi fc / fs), maps a normalised pole p to
// z = (1 + K p) / (1 - K p); the zeros of a low-pass land at z = -1.
LowPassFilter bilinear_lowpass(const std::vector<Complex>& poles, int order, double cutoff_hz,
                               double sample_rate_hz) {
  LowPassFilter filter;
  filter.order = order;
  filter.cutoff_hz = cutoff_hz;
  filter.sample_rate_hz = sample_rate_hz;
  const double k = std::tan(kPi * cutoff_hz / sample_rate_hz);
  for (const Complex& p : poles) {
    const Complex z = (1.0 + k * p) / (1.0 - k * p);
    LowPassFilter::Section s;
    if (p.imag() > 0) {
      // (1 - z z^-1)(1 - conj(z) z^-1) over g (1 + z^-1)^2.
      s.a1 = -2.0 * z.real();
      s.a2 = std::norm(z);
      const double g = (1.0 + s.a1 + s.a2) / 4.0;
      s.b0 = g;
      s.b1 = 2.0 * g;
      s.b2 = g;
    } else {
      s.a1 = -z.real();
      const double g = (1.0 + s.a1) / 2.0;
      s.b0 = g;
      s.b1 = g;
    }
    filter.sections.push_back(s);
  }
  return filter;
}

void check_design(int order, double cutoff_hz, double sample_rate_hz) {
  if (order < 1) {
    throw std::invalid_argument("filter order must be at least 1, got " + std::to_string(order));
  }
  if (!(sample_rate_hz > 0) || !std::isfinite(sample_rate_hz)) {
    throw std::invalid_argument("sample rate must be positive, got " + format(sample_rate_hz) +
                                " Hz");
  }
  if (!(cutoff_hz > 0) || !(cutoff_hz < sample_rate_hz / 2)) {
    throw std::invalid_argument("cut-off " + format(cutoff_hz) +
                                " Hz is not between 0 and the Nyquist frequency " +
                                format(sample_rate_hz / 2) + " Hz");
  }
}

}  // namespace

std::complex<double> LowPassFilter::response(double frequency_hz) const {
  const Complex zi = std::polar(1.0, -2.0 * kPi * frequency_hz / sample_rate_hz);  // z^-1
  Complex h = 1.0;
  for (const Section& s : sections) {
    h *= (s.b0 + zi * (s.b1 + zi * s.b2)) / (1.0 + zi * (s.a1 + zi * s.a2));
  }
  return h;
}

LowPassFilter butterworth_lowpass(int order, double cutoff_hz, double sample_rate_hz) {
  check_design(order, cutoff_hz, sample_rate_hz);
  // Normalised Butterworth poles exp(i pi (2k + n - 1) / (2n)), k = 1..n, on the left half
  // of the unit circle; k <= n/2 are those with Im > 0, and an odd order adds -1.
  std::vector<Complex> poles;
  for (int k = 1; 2 * k <= order; ++k) {
    poles.push_back(std::polar(1.0, kPi * (2.0 * k + order - 1.0) / (2.0 * order)));
  }
  if (order % 2 == 1) poles.emplace_back(-1.0, 0.0);
  return bilinear_lowpass(poles, order, cutoff_hz, sample_rate_hz);
}

LowPassFilter chebyshev1_lowpass(int order, double ripple_db, double cutoff_hz,
                                 double sample_rate_hz) {
  check_design(order, cutoff_hz, sample_rate_hz);
  if (!(ripple_db > 0) || !std::isfinite(ripple_db)) {
    throw std::invalid_argument("Chebyshev ripple must be positive, got " + format(ripple_db) +
                                " dB");
  }
  // Poles on an ellipse: -sinh(mu) sin(theta_k) + i cosh(mu) cos(theta_k), theta_k =
  // pi (2k - 1) / (2n), mu = asinh(1 / eps) / n, normalised to the ripple band edge.
  const double eps = std::sqrt(std::pow(10.0, ripple_db / 10.0) - 1.0);
  const double mu = std::asinh(1.0 / eps) / order;
  std::vector<Complex> poles;
  for (int k = 1; 2 * k <= order; ++k) {
    const double theta = kPi * (2.0 * k - 1.0) / (2.0 * order);
    poles.emplace_back(-std::sinh(mu) * std::sin(theta), std::cosh(mu) * std::cos(theta));
  }
  if (order % 2 == 1) poles.emplace_back(-std::sinh(mu), 0.0);
  return bilinear_lowpass(poles, order, cutoff_hz, sample_rate_hz);
}

void filter_causal(const LowPassFilter& filter, StridedMatrixRef x) {
  const Eigen::Index n = x.rows();
  std::vector<double> buffer(n), state;
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    for (Eigen::Index k = 0; k < n; ++k) buffer[k] = x(k, c);
    run_sections(filter, buffer.data(), n, false, state);
    for (Eigen::Index k = 0; k < n; ++k) x(k, c) = buffer[k];
  }
}

void filtfilt(const LowPassFilter& filter, StridedMatrixRef x) {
  const Eigen::Index n = x.rows();
  if (n == 0) return;
  const Eigen::Index settling = settling_samples(filter);
  std::vector<double> buffer, state;
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    const Eigen::Index pad = filtfilt_column(filter, x.col(c), settling, buffer, state);
    for (Eigen::Index k = 0; k < n; ++k) x(k, c) = buffer[pad + k];
  }
}

}  // namespace modelgen
