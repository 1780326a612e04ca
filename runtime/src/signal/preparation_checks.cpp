// The checks of a non-periodic preparation against its own data (issue 31).

#include "modelgen/signal/preparation_checks.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "modelgen/signal/band_power.hpp"
#include "modelgen/signal/filter_plan.hpp"
#include "modelgen/signal/lowpass.hpp"
#include "runtime/src/signal/dft.hpp"
#include "runtime/src/signal/trajectory_checks.hpp"

namespace modelgen {

namespace {

constexpr double kPi = std::numbers::pi;

// A kept band beyond kWideKeptBand times the excitation's is called too wide when over
// kNoisyShare of the torques' power lies in it above twice the excitation band (noise then
// fills the equations; on clean data it does no harm).
constexpr double kWideKeptBand = 10.0;
constexpr double kNoisyShare = 0.1;

// The variance of `x` after a zero-phase Butterworth low-pass at `band_hz` (all of it when the
// band reaches Nyquist).
double band_variance(const Eigen::VectorXd& x, double band_hz, double sample_rate_hz) {
  Eigen::MatrixXd y = x;
  if (band_hz < 0.45 * sample_rate_hz) filtfilt(butterworth_lowpass(4, band_hz, sample_rate_hz), y);
  return (y.array() - y.mean()).square().mean();
}

std::string format(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

std::string warning(const PreparationFacts& f, const std::string& text) {
  return (f.source.empty() ? std::string("data") : f.source) + ": warning: " + text;
}

}  // namespace

Eigen::VectorXd position_noise_std(const Trajectory& x) {
  const Eigen::Index n = x.q.rows();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(x.q.cols());
  if (n < 64) return out;
  const Eigen::Index fft_size = detail::next_power_of_two(n), half = fft_size / 2;
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> windowed(fft_size), spectrum;
  const Eigen::ArrayXd k = Eigen::ArrayXd::LinSpaced(n, 0, static_cast<double>(n - 1));
  const Eigen::ArrayXd hann = 0.5 - 0.5 * (2.0 * kPi / static_cast<double>(n - 1) * k).cos();
  const double energy = hann.square().sum();  // E|X_l|^2 = sigma^2 sum w^2 for white noise
  const double mean_k = k.mean();
  std::vector<double> lines;
  for (Eigen::Index j = 0; j < x.q.cols(); ++j) {
    const double mean_q = x.q.col(j).mean();
    const double slope =
        ((k - mean_k) * (x.q.col(j).array() - mean_q)).sum() / (k - mean_k).square().sum();
    std::fill(windowed.begin(), windowed.end(), 0.0);
    for (Eigen::Index s = 0; s < n; ++s) {
      windowed[s] = hann[s] * (x.q(s, j) - mean_q - slope * (k[s] - mean_k));
    }
    fft.fwd(spectrum, windowed);
    lines.clear();
    for (Eigen::Index l = half / 2; l < half; ++l) lines.push_back(std::norm(spectrum[l]));
    auto middle = lines.begin() + static_cast<std::ptrdiff_t>(lines.size() / 2);
    std::nth_element(lines.begin(), middle, lines.end());
    out[j] = std::sqrt(*middle / std::log(2.0) / energy);
  }
  return out;
}

double acceleration_noise_std(double q_std, double cutoff_hz, double kept_hz,
                              double sample_rate_hz) {
  // Power density 2 q_std^2 / fs (one-sided) through the second difference,
  // |(2 - 2 cos(2 pi f / fs)) fs^2|^2, the position filter run twice, |H|^4, and the
  // decimation's (Chebyshev I order 8 at the kept band, as decimation_filter, zero phase);
  // midpoint rule. Sampling after the decimation filter keeps the variance.
  const LowPassFilter filter = butterworth_lowpass(4, cutoff_hz, sample_rate_hz);
  const bool decimated = kept_hz < 0.45 * sample_rate_hz;
  const LowPassFilter kept =
      decimated ? chebyshev1_lowpass(8, 0.05, kept_hz, sample_rate_hz) : filter;
  const double top = 0.5 * sample_rate_hz;
  const int points = 20000;
  double variance = 0;
  for (int k = 0; k < points; ++k) {
    const double f = (k + 0.5) * top / points;
    const double d2 =
        (2 - 2 * std::cos(2 * kPi * f / sample_rate_hz)) * sample_rate_hz * sample_rate_hz;
    const double gain =
        std::norm(filter.response(f)) * (decimated ? std::norm(kept.response(f)) : 1.0);
    variance += d2 * d2 * gain * gain * top / points;
  }
  return q_std * std::sqrt(2 * variance / sample_rate_hz);
}

std::vector<std::string> check_preparation(const PreparationFacts& f) {
  std::vector<std::string> out;
  const double kept_hz =
      f.decimation > 1 ? 0.4 * f.sample_rate_hz / f.decimation : f.sample_rate_hz / 2;
  const double effective_hz = std::min(f.cutoff_hz, kept_hz);
  // Errors in the variables: least squares with noise in a regressor column shrinks its
  // coefficient by 1 / (1 + noise variance / signal variance); the inertia columns carry ddq.
  const double motion_band = std::min(2 * f.bandwidth_hz, effective_hz);
  double worst = 0;
  Eigen::Index worst_axis = -1;
  double worst_noise = 0, worst_motion = 0;
  for (Eigen::Index j = 0; j < f.q_noise_std.size() && j < f.ddq.cols(); ++j) {
    const double noise =
        acceleration_noise_std(f.q_noise_std[j], f.cutoff_hz, kept_hz, f.sample_rate_hz);
    // The motion's accelerations: the prepared ones within twice the excitation band, where
    // the noise (subtracted) is small against them.
    const double motion =
        std::max(band_variance(f.ddq.col(j), motion_band, f.sample_rate_hz) -
                     std::pow(acceleration_noise_std(f.q_noise_std[j], f.cutoff_hz, motion_band,
                                                     f.sample_rate_hz),
                              2),
                 1e-300);
    const double ratio = noise * noise / motion;
    if (ratio > worst) {
      worst = ratio;
      worst_axis = j;
      worst_noise = noise;
      worst_motion = std::sqrt(motion);
    }
  }
  if (worst > kAttenuationRatio) {
    out.push_back(warning(
        f, "errors in the variables: the positions carry " + format(f.q_noise_std[worst_axis]) +
               " rms of white noise (read from their spectrum "
               "above fs / 4), which leaves " +
               format(worst_noise) + " rms in the accelerations up to " + format(effective_hz) +
               " Hz against " + format(worst_motion) + " rms of motion on axis " +
               std::to_string(worst_axis + 1) + ": the inertia terms shrink by about " +
               format(100 * worst / (1 + worst)) + " %; the position filter (" +
               format(f.cutoff_hz) +
               " Hz) or the decimation's band is too wide for this noise: lower --cutoff or "
               "raise --decimate (the plan for these data: --cutoff " +
               format(f.planned_cutoff_hz) + " --decimate " + std::to_string(f.planned_decimation) +
               ")"));
  }
  const double rows = static_cast<double>(f.samples / std::max(f.decimation, 1)) *
                      static_cast<double>(f.ddq.cols());
  // The plan keeps the rows itself when it can; a record too short for that is not the
  // decimation's fault (and a short record is often refused for other reasons).
  if (f.decimation_given && f.unknowns > 0 && rows < kRowsPerParameter * f.unknowns) {
    out.push_back(
        warning(f, "the decimation by " + std::to_string(f.decimation) + " leaves about " +
                       format(rows) + " rows for " + std::to_string(f.unknowns) +
                       " parameters, fewer than " + format(kRowsPerParameter) +
                       " per parameter: few parameters will be well "
                       "determined and their standard deviations rest on few degrees of freedom; " +
                       "lower --decimate" + " (the plan for these data: --decimate " +
                       std::to_string(f.planned_decimation) + ")"));
  }
  // The share of the measured torques' power in the kept band that lies above twice the
  // excitation band: noise and what the model leaves out, kept in the equations.
  double noisy_share = 0;
  if (f.tau.rows() > 4) {
    const double dt = 1 / f.sample_rate_hz, beyond = power_above(f.tau, dt, kept_hz);
    const double kept = power_above(f.tau, dt, 0) - beyond;
    if (kept > 0) noisy_share = (power_above(f.tau, dt, 2 * f.bandwidth_hz) - beyond) / kept;
  }
  const bool wide = kept_hz > kWideKeptBand * f.bandwidth_hz && noisy_share > kNoisyShare;
  if ((f.decimation_given || f.cutoff_given) && f.bandwidth_hz > 0 &&
      (kept_hz > f.cutoff_hz || wide)) {
    out.push_back(warning(
        f, "the decimation by " + std::to_string(f.decimation) + " keeps up to " + format(kept_hz) +
               " Hz, " + format(kept_hz / f.bandwidth_hz) + " times the excitation's " +
               format(f.bandwidth_hz) + " Hz" +
               (kept_hz > f.cutoff_hz ? " and above the position filter's " + format(f.cutoff_hz) +
                                            " Hz (the torques keep there what the regressor lost)"
                                      : std::string()) +
               "; " + format(100 * noisy_share) +
               " % of the torques' power lies there, above "
               "the motion (under a controller, its answer to the encoder noise, coloured, while "
               "the standard deviations assume white residuals); "
               "raise --decimate (the plan for these data: --decimate " +
               std::to_string(f.planned_decimation) + ")"));
  }
  return out;
}

}  // namespace modelgen
