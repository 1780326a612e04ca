// The cascade of second-order sections, run in place over a buffer from a steady state.

#include "runtime/src/signal/filter_sections.hpp"

#include <cmath>
#include <complex>

namespace modelgen::detail {

namespace {

// Group delay at DC, in samples, of one section: sum k b_k / sum b_k - sum k a_k / sum a_k.
double dc_delay(const LowPassFilter::Section& s) {
  return (s.b1 + 2.0 * s.b2) / (s.b0 + s.b1 + s.b2) - (s.a1 + 2.0 * s.a2) / (1.0 + s.a1 + s.a2);
}

}  // namespace

Eigen::Index settling_samples(const LowPassFilter& filter) {
  using Complex = std::complex<double>;
  double radius = 0;
  for (const LowPassFilter::Section& s : filter.sections) {
    // Poles: roots of z^2 + a1 z + a2.
    const Complex root = std::sqrt(Complex(s.a1 * s.a1 - 4.0 * s.a2, 0.0));
    radius = std::max({radius, std::abs((-s.a1 + root) / 2.0), std::abs((-s.a1 - root) / 2.0)});
  }
  if (radius <= 0) return 1;
  if (radius >= 1) return Eigen::Index{1} << 40;  // unstable or marginal: as long as the data
  return static_cast<Eigen::Index>(std::ceil(10.0 / -std::log(radius))) + 1;
}

void run_sections(const LowPassFilter& filter, double* u, Eigen::Index len, bool backward,
                  std::vector<double>& state) {
  if (len == 0) return;
  const std::size_t count = filter.sections.size();
  state.resize(2 * count);
  const LowPassFilter::Section* sec = filter.sections.data();
  const Eigen::Index step = backward ? -1 : 1;
  double* p = backward ? u + len - 1 : u;
  double v0 = p[0];
  const double slope = len > 1 ? p[step] - p[0] : 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const LowPassFilter::Section& s = sec[i];
    const double delay = dc_delay(s);
    // Input and output one and two samples before the first.
    const double v1 = v0 - slope, v2 = v0 - 2.0 * slope;
    const double y1 = v0 - (1.0 + delay) * slope, y2 = v0 - (2.0 + delay) * slope;
    state[2 * i + 1] = s.b2 * v1 - s.a2 * y1;
    state[2 * i] = s.b1 * v1 - s.a1 * y1 + s.b2 * v2 - s.a2 * y2;
    v0 -= delay * slope;  // the next section's input at the first sample
  }
  double* z = state.data();
  for (Eigen::Index k = 0; k < len; ++k, p += step) {
    double v = *p;
    for (std::size_t i = 0; i < count; ++i) {
      const LowPassFilter::Section& s = sec[i];
      const double y = s.b0 * v + z[2 * i];
      z[2 * i] = s.b1 * v - s.a1 * y + z[2 * i + 1];
      z[2 * i + 1] = s.b2 * v - s.a2 * y;
      v = y;
    }
    *p = v;
  }
}

}  // namespace modelgen::detail
