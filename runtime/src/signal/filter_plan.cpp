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

#include "modelgen/signal/decimation.hpp"
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

// Lines above kSignificance times the local mean noise power are motion.
constexpr double kSignificance = 20.0;
// The noise floor is estimated per band of at least kMinBandLines lines, bands growing by
// kBandRatio (an eighth of an octave) so that a coloured floor is followed: noise falling as
// f^-4 changes by a factor 1.4 within such a band.
constexpr Eigen::Index kMinBandLines = 128;
constexpr double kBandRatio = 1.09;
// The floor of a band is a low quantile of its lines: motion may fill a good part of a band (a
// contiguous excitation spectrum) without lifting it. For exponentially distributed noise
// powers, the quartile is -ln(0.75) = 0.288 times their mean.
constexpr double kFloorQuantile = 0.25;

// The mean noise power under each line of a power spectrum (lines 0..half): a floor that
// follows the spectrum's colour. Noise in measured positions is seldom white: timing jitter,
// positions resampled by interpolation or held between updates (the Panda's logs) give a floor
// that falls with frequency, and a floor taken from the top of the band alone then passes the
// noise at mid frequencies off as motion, which differentiation weighs by f^2.
Eigen::VectorXd local_noise_floor(const Eigen::VectorXd& power) {
  const Eigen::Index lines = power.size();
  Eigen::VectorXd floor = Eigen::VectorXd::Zero(lines);
  std::vector<double> band;
  for (Eigen::Index first = 1; first < lines;) {  // line 0 (the mean) is no motion
    const Eigen::Index width = std::max(
        kMinBandLines, static_cast<Eigen::Index>(static_cast<double>(first) * (kBandRatio - 1)));
    // A short last band joins the previous one.
    const Eigen::Index last = lines - (first + width) < width / 2 ? lines : first + width;
    band.assign(power.data() + first, power.data() + last);
    const auto rank = static_cast<std::ptrdiff_t>(kFloorQuantile * static_cast<double>(band.size()));
    std::nth_element(band.begin(), band.begin() + rank, band.end());
    floor.segment(first, last - first).setConstant(band[rank] / -std::log(1.0 - kFloorQuantile));
    first = last;
  }
  return floor;
}

// The frequency below which `fraction` of the energy of the columns' significant lines lies,
// each line's power weighted by (2 pi f)^(2 derivative): the bandwidth of the derivative-th
// derivative. Per column: its least-squares line removed (a ramp would leak over the whole
// spectrum), Hann window, power spectrum, local_noise_floor. Returns a negative value when no
// line stands out of the noise.
double significant_band(const Eigen::MatrixXd& x, double dt, int derivative, double fraction) {
  const Eigen::Index n = x.rows();
  const Eigen::Index fft_size = next_power_of_two(n), half = fft_size / 2;
  Eigen::FFT<double> fft;
  std::vector<Complex> windowed(fft_size), spectrum;
  Eigen::VectorXd line_power(half + 1), weighted = Eigen::VectorXd::Zero(half + 1);
  const Eigen::ArrayXd k = Eigen::ArrayXd::LinSpaced(n, 0, static_cast<double>(n - 1));
  const Eigen::ArrayXd hann = 0.5 - 0.5 * (2.0 * kPi / static_cast<double>(n - 1) * k).cos();
  const double mean_k = k.mean();
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const double mean_x = x.col(j).mean();
    const double slope =
        ((k - mean_k) * (x.col(j).array() - mean_x)).sum() / (k - mean_k).square().sum();
    std::fill(windowed.begin(), windowed.end(), 0.0);
    for (Eigen::Index s = 0; s < n; ++s) {
      windowed[s] = hann[s] * (x(s, j) - mean_x - slope * (k[s] - mean_k));
    }
    fft.fwd(spectrum, windowed);
    for (Eigen::Index l = 0; l <= half; ++l) line_power[l] = std::norm(spectrum[l]);
    const Eigen::VectorXd floor = local_noise_floor(line_power);
    for (Eigen::Index l = 1; l <= half; ++l) {
      // A line counts when noise alone would exceed it with a probability of 2e-9 (the powers
      // of noise lines are exponentially distributed: P(p > c mean) = exp(-c)), so that among
      // some 10^5 lines of all axes none is taken for motion by chance.
      if (!(line_power[l] > kSignificance * floor[l])) continue;
      const double w = 2.0 * kPi * static_cast<double>(l) / (static_cast<double>(fft_size) * dt);
      weighted[l] += std::pow(w, 2 * derivative) * (line_power[l] - floor[l]);
    }
  }
  const double total = weighted.sum();
  if (!(total > 0)) return -1;
  double cumulative = 0;
  Eigen::Index line = 0;
  for (; line < half; ++line) {
    cumulative += weighted[line];
    if (cumulative >= fraction * total) break;
  }
  return static_cast<double>(line) / (static_cast<double>(fft_size) * dt);
}

}  // namespace

double estimate_bandwidth(const Trajectory& x, double energy_fraction) {
  return estimate_bands(x, energy_fraction).bandwidth_hz;
}

ExcitationBands estimate_bands(const Trajectory& x, double energy_fraction) {
  if (!(energy_fraction > 0) || !(energy_fraction < 1)) {
    throw std::invalid_argument("energy fraction must be between 0 and 1, got " +
                                format(energy_fraction));
  }
  const double dt = uniform_sample_time(x);
  check_shapes(x, false);
  check_finite(x, x.q, "q");
  if (x.t.size() < 16) fail(x, "fewer than 16 samples to estimate a bandwidth from");
  ExcitationBands out;
  out.velocity_hz = significant_band(x.q, dt, 1, energy_fraction);
  if (out.velocity_hz < 0) fail(x, "the positions do not move above their noise: no bandwidth");
  // Gautier & Briot eq. 13-14: the decimation must keep the band of both sides of
  // tau = W beta. W is nonlinear in the motion (sines of q, products of velocities) and holds
  // friction, so the torques reach above the motion's band; the measured torques show how far.
  if (x.measured != Measured::kNothing && x.tau.allFinite()) {
    out.torque_hz = std::max(significant_band(x.tau, dt, 0, energy_fraction), 0.0);
  }
  out.bandwidth_hz = std::max(out.velocity_hz, out.torque_hz);
  return out;
}

FilterPlan plan_filtering(double sample_rate_hz, double bandwidth_hz, const RowBudget& rows) {
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
  // Two bounds on n_d: the band it keeps and the rows it leaves; the smaller one decides.
  const int by_band =
      std::max(1, static_cast<int>(std::floor(0.8 * nyquist / (kKeptBandMultiple * bandwidth_hz))));
  int by_rows = by_band;
  if (rows.unknowns > 0 && rows.axes > 0 && rows.samples > 0) {
    by_rows =
        std::max(1, static_cast<int>(std::floor(static_cast<double>(rows.samples) * rows.axes /
                                                (kRowsPerParameter * rows.unknowns))));
  }
  const bool row_bound = by_rows < by_band;
  // The largest factor the rule allows that runs in stages of at most 10 (decimation_stages).
  plan.decimation_factor = decimation_factor_below(std::min(by_band, by_rows));
  plan.decimation_cutoff_hz = 0.8 * nyquist / plan.decimation_factor;
  std::string text =
      "positions: zero-phase Butterworth order " + std::to_string(plan.position_order) + " at " +
      format(plan.position_cutoff_hz) + " Hz (" + (capped ? "0.8 x Nyquist, below 10 x" : "10 x") +
      " the " + format(bandwidth_hz) + " Hz bandwidth); ";
  const std::string why =
      row_bound
          ? "the largest that leaves " + format(kRowsPerParameter) + " rows per parameter (" +
                std::to_string(rows.samples) + " samples x " + std::to_string(rows.axes) +
                " axes for " + std::to_string(rows.unknowns) + " parameters)"
          : "the largest whose filter keeps " + format(kKeptBandMultiple) + " x the bandwidth";
  if (plan.decimation_factor == 1) {
    text += "torques and regressor not decimated (" + why + ")";
  } else {
    std::string stages;
    for (int stage : decimation_stages(plan.decimation_factor)) {
      stages += (stages.empty() ? "" : " x ") + std::to_string(stage);
    }
    text += "torques and regressor decimated by " + std::to_string(plan.decimation_factor) + " (" +
            format(sample_rate_hz) + " Hz to " + format(sample_rate_hz / plan.decimation_factor) +
            " Hz in stages " + stages + ", Chebyshev I order 8 zero-phase, last cut-off " +
            format(plan.decimation_cutoff_hz) + " Hz; " + why + ")";
  }
  plan.explanation = text;
  return plan;
}

}  // namespace modelgen
