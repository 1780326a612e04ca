// The excitation band of a record and the split of a torque comparison's energies at it: what
// lies above the band, and the noise inside it (from the change between periods, or the low
// quartile of the error's spectrum), by Hann-windowed DFTs.

#include "modelgen/signal/noise_floor.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "modelgen/signal/filter_plan.hpp"
#include "modelgen/signal/period.hpp"
#include "runtime/src/signal/dft.hpp"
#include "runtime/src/signal/trajectory_checks.hpp"

namespace modelgen {

namespace {

using detail::format;

// The powers of noise lines are exponentially distributed: their lower quartile is
// -ln(0.75) = 0.288 times their mean.
constexpr double kQuartile = 0.25;
// Fewer noise lines than this in the band give no estimate worth printing.
constexpr Eigen::Index kMinNoiseLines = 4;
// A period whose samples drift by more than this over the record is not aligned.
constexpr double kMaxMisalignment = 0.25;  // samples

// |X_l|^2, l = 0..n-1, of a column under a Hann window, and the window's sum of squares. The
// window's sidelobes fall as 1 / distance^3 (a rectangular window's as 1 / distance): content
// far above the band (a controller's noise, a resonance) and the jump between a record's
// ends stay out of the band's lines.
struct WindowedSpectrum {
  std::vector<double> power;
  double window_energy = 0;
};

WindowedSpectrum windowed_spectrum(const Eigen::Ref<const Eigen::VectorXd>& x) {
  const Eigen::Index n = x.size();
  Eigen::VectorXd y(n);
  WindowedSpectrum out;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double w = n < 2 ? 1.0
                           : 0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(k) /
                                                  static_cast<double>(n - 1));
    y[k] = w * x[k];
    out.window_energy += w * w;
  }
  const std::vector<std::complex<double>> spectrum = detail::dft(y);
  out.power.resize(n);
  for (Eigen::Index l = 0; l < n; ++l) out.power[l] = std::norm(spectrum[l]);
  return out;
}

// The frequency index of DFT line l of n (lines above n / 2 are the negative frequencies).
Eigen::Index frequency_index(Eigen::Index l, Eigen::Index n) { return std::min(l, n - l); }

// The last line in the band: lines 0..edge lie at or below band_hz.
Eigen::Index band_edge(double band_hz, Eigen::Index n, double dt) {
  return static_cast<Eigen::Index>(std::floor(band_hz * static_cast<double>(n) * dt + 1e-9));
}

// The energy in the band (sum of squares, columns summed): per column its energy times the
// share of its windowed spectrum in the band.
double energy_in_band(const Eigen::MatrixXd& x, double dt, double band_hz) {
  const Eigen::Index n = x.rows(), edge = band_edge(band_hz, n, dt);
  double energy = 0;
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const std::vector<double> power = windowed_spectrum(x.col(j)).power;
    double in = 0, all = 0;
    for (Eigen::Index l = 0; l < n; ++l) {
      all += power[l];
      if (frequency_index(l, n) <= edge) in += power[l];
    }
    if (all > 0) energy += x.col(j).squaredNorm() * in / all;
  }
  return energy;
}

// Periodic data: the noise energy in the band from the differences of consecutive periods,
// d_k = e_k+N - e_k. What repeats every period (the excitation, what a model of it explains)
// cancels; the noise is left, its power multiplied by |1 - exp(-i w N dt)|^2 = 4 sin^2(w N dt
// / 2), 2 on average over a band of whole harmonics: the noise in the band is half the
// differences' energy there, per sample.
double noise_from_periods(const Eigen::MatrixXd& error, double dt, double band_hz,
                          Eigen::Index samples_per_period) {
  const Eigen::Index n = error.rows(), m = n - samples_per_period;
  const Eigen::MatrixXd differences = error.bottomRows(m) - error.topRows(m);
  return 0.5 * energy_in_band(differences, dt, band_hz) * static_cast<double>(n) /
         static_cast<double>(m);
}

// The noise energy in the band from the lower quartile of the error's windowed line powers
// there: mean line power / window energy is the noise power per line, of 2 edge + 1 lines.
double noise_from_quartile(const Eigen::MatrixXd& error, double dt, double band_hz) {
  const Eigen::Index n = error.rows(), edge = band_edge(band_hz, n, dt);
  double noise = 0;
  for (Eigen::Index j = 0; j < error.cols(); ++j) {
    const WindowedSpectrum spectrum = windowed_spectrum(error.col(j));
    std::vector<double> band;
    // Lines 0 and 1 hold the mean (the window spreads it over a line each side).
    for (Eigen::Index l = 0; l < n; ++l) {
      const Eigen::Index f = frequency_index(l, n);
      if (f >= 2 && f <= edge) band.push_back(spectrum.power[l]);
    }
    if (static_cast<Eigen::Index>(band.size()) < kMinNoiseLines) {
      return std::numeric_limits<double>::quiet_NaN();
    }
    const auto rank = static_cast<std::ptrdiff_t>(kQuartile * static_cast<double>(band.size()));
    std::nth_element(band.begin(), band.begin() + rank, band.end());
    noise += band[rank] / -std::log(1.0 - kQuartile) / spectrum.window_energy *
             static_cast<double>(2 * edge + 1);
  }
  return noise;
}

double ratio(double numerator, double denominator) {
  return denominator > 0 ? numerator / denominator : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

ExcitationBand band_of_fourier(const FourierTrajectory& fourier, const std::string& source) {
  Eigen::Index top = 0;
  for (Eigen::Index l = 0; l < fourier.a.cols(); ++l) {
    if ((fourier.a.col(l).array() != 0).any() || (fourier.b.col(l).array() != 0).any()) top = l + 1;
  }
  if (top == 0) {
    throw DataError(source + ": error: the excitation has no harmonic: no band to compare in");
  }
  ExcitationBand band;
  band.period = fourier.period;
  band.band_hz = kTorqueBandFactor * static_cast<double>(top) / fourier.period;
  band.origin = format(kTorqueBandFactor) + " x harmonic " + std::to_string(top) + " of " + source +
                " (period " + format(fourier.period) + " s)";
  return band;
}

ExcitationBand band_of_positions(const Trajectory& positions) {
  Trajectory motion = positions;
  motion.measured = Measured::kNothing;  // the band of the motion, not of the torques
  ExcitationBand band;
  band.band_hz = kTorqueBandFactor * estimate_bands(motion).velocity_hz;
  band.origin = format(kTorqueBandFactor) + " x the band of 99% of the velocities' energy";
  try {
    band.period = detect_period(motion);
    band.origin += ", period " + format(band.period) + " s found in the positions";
  } catch (const DataError&) {
    band.period = 0;  // not periodic: the noise comes from the spectrum alone
  }
  return band;
}

BandEnergies band_energies(const Eigen::MatrixXd& tau, const Eigen::MatrixXd& error, double dt,
                           const ExcitationBand& band) {
  if (tau.rows() != error.rows() || tau.cols() != error.cols()) {
    throw std::invalid_argument("band_energies: torque and error matrices differ in shape");
  }
  if (!(dt > 0)) throw std::invalid_argument("band_energies: sample time must be positive");
  BandEnergies out;
  out.band = band;
  out.values = static_cast<long long>(tau.size());
  out.torque = tau.squaredNorm();
  out.error = error.squaredNorm();
  out.torque_above = out.torque - energy_in_band(tau, dt, band.band_hz);
  out.error_above = out.error - energy_in_band(error, dt, band.band_hz);
  const Eigen::Index n = tau.rows();
  if (band.period > 0) {
    const double exact = band.period / dt;
    const auto per_period = static_cast<Eigen::Index>(std::llround(exact));
    const Eigen::Index periods = per_period > 0 ? n / per_period : 0;
    const bool aligned =
        std::abs(exact - static_cast<double>(per_period)) * static_cast<double>(periods) <=
        kMaxMisalignment;
    // The differences span periods - 1 periods: their band needs lines to average over.
    const Eigen::Index difference_lines =
        per_period > 0 ? band_edge(band.band_hz, n - per_period, dt) : 0;
    if (periods >= 2 && aligned && difference_lines >= kMinNoiseLines) {
      out.noise_in_band = noise_from_periods(error, dt, band.band_hz, per_period);
      out.noise_periods = periods;
      out.noise_origin =
          "the error's change from period to period, over " + std::to_string(periods) + " periods";
      return out;
    }
  }
  out.noise_in_band = noise_from_quartile(error, dt, band.band_hz);
  out.noise_origin = std::isnan(out.noise_in_band)
                         ? "not estimated: too few spectral lines in the band"
                         : "the lower quartile of the error's spectrum in the band";
  return out;
}

NoiseFloor noise_floor(const std::vector<BandEnergies>& records) {
  double torque = 0, torque_above = 0, error = 0, error_above = 0, noise = 0, values = 0;
  for (const BandEnergies& r : records) {
    values += static_cast<double>(r.values);
    torque += r.torque;
    torque_above += r.torque_above;
    error += r.error;
    error_above += r.error_above;
    noise += r.noise_in_band;  // NaN stays NaN: one record without an estimate, none pooled
  }
  const double torque_in = std::max(torque - torque_above, 0.0);
  const double error_in = std::max(error - error_above, 0.0);
  NoiseFloor out;
  out.full_band = std::sqrt(ratio(error, torque));
  out.in_band = std::sqrt(ratio(error_in, torque_in));
  out.out_of_band_fraction = ratio(torque_above, torque);
  out.floor = std::sqrt(ratio(noise, torque_in));
  out.in_band_rms = std::sqrt(ratio(error_in, values));
  out.floor_rms = std::sqrt(ratio(noise, values));
  out.in_band_headline = out.out_of_band_fraction > kOutOfBandDominates;
  return out;
}

}  // namespace modelgen
