// The independence test of the position and torque errors of a periodic record: band
// coherences of their period-to-period deviations, combined by Fisher's method (the
// derivation is in the header).

#include "modelgen/signal/noise_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

namespace modelgen {

namespace {

// Complex degrees of freedom per band: enough that a band's coherence under independence is
// small (mean 1 / K) and the bias-corrected correlation is steady.
constexpr int kDegreesPerBand = 16;
// A band holds rounding, not noise, when its energy is below this fraction of the axis's
// largest band (a filter's stop band), or when its noise, as a standard deviation per sample,
// is below kRounding times the signal's largest value (exact, e.g. simulated, positions).
constexpr double kNoNoise = 1e-20, kRounding = 1e-12;

// Wilson-Hilferty: (X / nu)^(1/3) of a chi-square X with nu degrees of freedom is about
// normal with mean 1 - 2 / (9 nu) and variance 2 / (9 nu).
double chi_square_z(double x, double nu) {
  const double s = 2.0 / (9.0 * nu);
  return (std::cbrt(x / nu) - (1.0 - s)) / std::sqrt(s);
}

struct Band {
  double q = 0, tau = 0;
  std::complex<double> cross;
};

}  // namespace

NoiseCoupling noise_coupling(const PeriodicAverage& average) {
  NoiseCoupling out;
  const int periods = average.periods;
  const Eigen::Index lines = (average.samples_per_period - 1) / 2;  // 1..lines
  if (periods < 2 || average.tau_q_line_covariance.size() == 0) return out;
  const int width = (kDegreesPerBand + periods - 2) / (periods - 1);
  const Eigen::Index band_count = lines / width;
  if (band_count < 1) return out;
  out.lines_per_band = width;
  out.degrees = width * (periods - 1);
  const double k = out.degrees;
  const Eigen::Index dof = average.q_line_variance.cols();
  out.correlation = out.z = out.chi_square = Eigen::VectorXd::Zero(dof);
  out.bands = Eigen::VectorXi::Zero(dof);
  std::vector<Band> bands(band_count);
  for (Eigen::Index j = 0; j < dof; ++j) {
    double largest_q = 0, largest_tau = 0;
    for (Eigen::Index b = 0; b < band_count; ++b) {
      Band& band = bands[b];
      band = Band{};
      for (Eigen::Index l = 1 + b * width; l <= (b + 1) * width; ++l) {
        band.q += average.q_line_variance(l, j);
        band.tau += average.tau_line_variance(l, j);
        band.cross += average.tau_q_line_covariance(l, j);
      }
      largest_q = std::max(largest_q, band.q);
      largest_tau = std::max(largest_tau, band.tau);
    }
    // A line of white noise of variance s^2 per averaged sample has E|E_l|^2 = N s^2.
    const double lines_in_band = static_cast<double>(width * average.samples_per_period);
    const double q_floor = std::max(
        kNoNoise * largest_q,
        lines_in_band * std::pow(kRounding * average.averaged.q.col(j).cwiseAbs().maxCoeff(), 2));
    const double tau_floor = std::max(
        kNoNoise * largest_tau,
        lines_in_band * std::pow(kRounding * average.averaged.tau.col(j).cwiseAbs().maxCoeff(), 2));
    double explained = 0, energy = 0;
    for (const Band& band : bands) {
      if (!(band.q > q_floor) || !(band.tau > tau_floor)) continue;
      const double coherence = std::min(std::norm(band.cross) / (band.q * band.tau), 1.0 - 1e-15);
      out.chi_square[j] += -2.0 * (k - 1.0) * std::log1p(-coherence);
      ++out.bands[j];
      explained += coherence * band.tau;
      energy += band.tau;
    }
    if (out.bands[j] == 0) continue;
    out.z[j] = chi_square_z(out.chi_square[j], 2.0 * out.bands[j]);
    // Under independence a band's coherence averages 1 / K whatever its energy.
    const double fraction = (explained - energy / k) / (energy * (1.0 - 1.0 / k));
    out.correlation[j] = std::sqrt(std::max(fraction, 0.0));
  }
  return out;
}

}  // namespace modelgen
