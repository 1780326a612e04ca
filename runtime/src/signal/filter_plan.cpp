// The excitation bandwidth from the spectrum of the positions, and Gautier's rule for the
// position filter's cut-off and the decimation factor.

#include "modelgen/signal/filter_plan.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "modelgen/signal/sampling.hpp"
#include "runtime/src/signal/dft.hpp"
#include "runtime/src/signal/trajectory_checks.hpp"

namespace modelgen {

namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;
using detail::check_finite;
using detail::check_shapes;
using detail::fail;
using detail::format;
using detail::next_power_of_two;

}  // namespace

double estimate_bandwidth(const Trajectory& x, double energy_fraction) {
  if (!(energy_fraction > 0) || !(energy_fraction < 1)) {
    throw std::invalid_argument("energy fraction must be between 0 and 1, got " +
                                format(energy_fraction));
  }
  const double dt = uniform_sample_time(x);
  check_shapes(x, false);
  check_finite(x, x.q, "q");
  const Eigen::Index n = x.t.size(), dof = x.q.cols();
  if (n < 16) fail(x, "fewer than 16 samples to estimate a bandwidth from");
  const Eigen::Index fft_size = next_power_of_two(n), half = fft_size / 2;
  Eigen::FFT<double> fft;
  std::vector<Complex> windowed(fft_size), spectrum;
  Eigen::VectorXd line_power(half + 1), velocity_power = Eigen::VectorXd::Zero(half + 1);
  const Eigen::ArrayXd k = Eigen::ArrayXd::LinSpaced(n, 0, static_cast<double>(n - 1));
  const Eigen::ArrayXd hann = 0.5 - 0.5 * (2.0 * kPi / static_cast<double>(n - 1) * k).cos();
  for (Eigen::Index j = 0; j < dof; ++j) {
    // Least-squares line through the axis: a ramp would leak over the whole spectrum.
    const double mean_k = k.mean(), mean_q = x.q.col(j).mean();
    const double slope =
        ((k - mean_k) * (x.q.col(j).array() - mean_q)).sum() / (k - mean_k).square().sum();
    std::fill(windowed.begin(), windowed.end(), 0.0);
    for (Eigen::Index s = 0; s < n; ++s) {
      windowed[s] = hann[s] * (x.q(s, j) - mean_q - slope * (k[s] - mean_k));
    }
    fft.fwd(spectrum, windowed);
    for (Eigen::Index l = 0; l <= half; ++l) line_power[l] = std::norm(spectrum[l]);
    // Noise floor from the top half of the band: the median of exponentially distributed
    // powers is ln 2 times their mean.
    std::vector<double> top(line_power.data() + half / 2, line_power.data() + half + 1);
    std::nth_element(top.begin(), top.begin() + top.size() / 2, top.end());
    const double floor = 10.0 * top[top.size() / 2] / std::numbers::ln2;
    for (Eigen::Index l = 1; l <= half; ++l) {
      const double w = 2.0 * kPi * static_cast<double>(l) / (static_cast<double>(fft_size) * dt);
      velocity_power[l] += w * w * std::max(line_power[l] - floor, 0.0);
    }
  }
  const double total = velocity_power.sum();
  if (!(total > 0)) fail(x, "the positions do not move above their noise: no bandwidth");
  double cumulative = 0;
  Eigen::Index line = 0;
  for (; line < half; ++line) {
    cumulative += velocity_power[line];
    if (cumulative >= energy_fraction * total) break;
  }
  return static_cast<double>(line) / (static_cast<double>(fft_size) * dt);
}

FilterPlan plan_filtering(double sample_rate_hz, double bandwidth_hz) {
  if (!(sample_rate_hz > 0) || !std::isfinite(sample_rate_hz)) {
    throw std::invalid_argument("sample rate must be positive, got " + format(sample_rate_hz) +
                                " Hz");
  }
  const double nyquist = sample_rate_hz / 2;
  if (!(bandwidth_hz > 0) || !(bandwidth_hz < nyquist)) {
    throw std::invalid_argument("bandwidth " + format(bandwidth_hz) +
                                " Hz is not between 0 and the Nyquist frequency " +
                                format(nyquist) + " Hz");
  }
  FilterPlan plan;
  plan.sample_rate_hz = sample_rate_hz;
  plan.bandwidth_hz = bandwidth_hz;
  const bool capped = 10.0 * bandwidth_hz > 0.8 * nyquist;
  plan.position_cutoff_hz = capped ? 0.8 * nyquist : 10.0 * bandwidth_hz;
  plan.decimation_factor =
      std::max(1, static_cast<int>(std::floor(0.8 * nyquist / (2.0 * bandwidth_hz))));
  plan.decimation_cutoff_hz = 0.8 * nyquist / plan.decimation_factor;
  std::string text =
      "positions: zero-phase Butterworth order " + std::to_string(plan.position_order) + " at " +
      format(plan.position_cutoff_hz) + " Hz (" + (capped ? "0.8 x Nyquist, below 10 x" : "10 x") +
      " the " + format(bandwidth_hz) + " Hz bandwidth); ";
  if (plan.decimation_factor == 1) {
    text +=
        "torques and regressor not decimated (a decimation filter at 2 x the bandwidth "
        "would need a higher sample rate)";
  } else {
    text += "torques and regressor decimated by " + std::to_string(plan.decimation_factor) + " (" +
            format(sample_rate_hz) + " Hz to " + format(sample_rate_hz / plan.decimation_factor) +
            " Hz, Chebyshev I order 8 zero-phase at " + format(plan.decimation_cutoff_hz) +
            " Hz, at least 2 x the bandwidth)";
  }
  plan.explanation = text;
  return plan;
}

}  // namespace modelgen
