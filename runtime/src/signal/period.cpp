// Periodic excitation (Swevers et al. 2002, section 4): period detection from the
// autocorrelation of the positions, averaging over whole periods and the noise variance of the
// averages.

#include "modelgen/signal/period.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "modelgen/signal/sampling.hpp"
#include "runtime/src/signal/dft.hpp"
#include "runtime/src/signal/trajectory_checks.hpp"

namespace modelgen {

namespace {

using Complex = std::complex<double>;
using detail::check_finite;
using detail::check_shapes;
using detail::fail;
using detail::format;
using detail::next_power_of_two;

constexpr double kMinCorrelation = 0.9, kDecorrelated = 0.5;

// Pooled Pearson correlation of q(k) with q(k + m) over the overlap, per lag m:
// r(m) = sum_j cov_j(m) / sum_j sqrt(var_a_j(m) var_b_j(m)), segment means removed, so each
// axis counts with its position variance. The lagged products come from one FFT per axis.
std::vector<double> lag_correlation(const Trajectory& x, Eigen::Index max_lag) {
  const Eigen::Index n = x.t.size(), dof = x.q.cols();
  const Eigen::Index fft_size = next_power_of_two(2 * n);
  Eigen::FFT<double> fft;
  std::vector<Complex> padded(fft_size), spectrum, power(fft_size, 0.0);
  std::vector<double> cov(max_lag + 1, 0.0), norm(max_lag + 1, 0.0);
  std::vector<double> sum(n + 1), sum_sq(n + 1);
  bool moves = false;
  for (Eigen::Index j = 0; j < dof; ++j) {
    // An axis that does not move says nothing (its rounding noise would correlate at random).
    const double mean = x.q.col(j).mean();
    const double range = x.q.col(j).maxCoeff() - x.q.col(j).minCoeff();
    if (!(range > 1e-12 * x.q.col(j).cwiseAbs().maxCoeff())) continue;
    sum[0] = sum_sq[0] = 0;
    std::fill(padded.begin(), padded.end(), 0.0);
    for (Eigen::Index k = 0; k < n; ++k) {
      const double v = x.q(k, j) - mean;
      padded[k] = v;
      sum[k + 1] = sum[k] + v;
      sum_sq[k + 1] = sum_sq[k] + v * v;
    }
    moves = true;
    fft.fwd(spectrum, padded);
    for (Eigen::Index k = 0; k < fft_size; ++k) power[k] += std::norm(spectrum[k]);
    for (Eigen::Index m = 0; m <= max_lag; ++m) {
      const Eigen::Index overlap = n - m;
      const double len = static_cast<double>(overlap);
      const double sa = sum[overlap], sb = sum[n] - sum[m];
      const double va = std::max(sum_sq[overlap] - sa * sa / len, 0.0);
      const double vb = std::max(sum_sq[n] - sum_sq[m] - sb * sb / len, 0.0);
      cov[m] -= sa * sb / len;
      norm[m] += std::sqrt(va * vb);
    }
  }
  if (!moves) fail(x, "no period found: the positions do not move");
  std::vector<Complex> lagged;
  fft.inv(lagged, power);  // sum_k q(k) q(k + m), summed over axes
  std::vector<double> r(max_lag + 1);
  for (Eigen::Index m = 0; m <= max_lag; ++m) {
    r[m] = norm[m] > 0 ? (lagged[m].real() + cov[m]) / norm[m] : 0.0;
  }
  return r;
}

// The first lag past the lobe around lag 0 (down to a clear decorrelation, so that a small
// vibration on a slow motion is not taken for a period).
Eigen::Index end_of_first_lobe(const Trajectory& x, const std::vector<double>& r) {
  const Eigen::Index max_lag = static_cast<Eigen::Index>(r.size()) - 1;
  Eigen::Index start = 1;
  while (start <= max_lag && r[start] >= kDecorrelated) ++start;
  if (start > max_lag) {
    fail(x,
         "no period found: the positions never decorrelate over the record (a drift or a "
         "motion slower than the record)");
  }
  return start;
}

// The lag of the highest correlation from `start` on, which must be a clear one.
Eigen::Index highest_correlation(const Trajectory& x, const std::vector<double>& r,
                                 Eigen::Index start, double dt) {
  const Eigen::Index max_lag = static_cast<Eigen::Index>(r.size()) - 1;
  Eigen::Index best = start;
  for (Eigen::Index m = start; m <= max_lag; ++m) {
    if (r[m] > r[best]) best = m;
  }
  if (r[best] < kMinCorrelation) {
    fail(x, "no period found: the positions never correlate with themselves again above " +
                format(kMinCorrelation) + " (best " + format(r[best]) + " at a lag of " +
                format(static_cast<double>(best) * dt) + " s)");
  }
  return best;
}

// The lag of the highest correlation in [from, to].
Eigen::Index peak_near(const std::vector<double>& r, Eigen::Index from, Eigen::Index to) {
  Eigen::Index at = from;
  for (Eigen::Index m = from; m <= to; ++m) {
    if (r[m] > r[at]) at = m;
  }
  return at;
}

// Sub-sample position of a peak: least-squares parabola over the lags d = -w..w around it.
// r is a smooth function of the lag plus a part that is white from lag to lag (noise
// correlated with noise), which more lags average out; but the peak is slightly asymmetric
// (the overlap shrinks as the lag grows), which biases wider fits. So w is the smallest
// window that brings the vertex's noise to 0.01 sample: its standard deviation is about
// s / (2 |c| sqrt(2 w^3 / 3)) for white noise s on r and curvature c, with s estimated from
// third differences of r (variance 20 s^2 for white noise) and c from the lag-0 lobe
// (r drops to 0.5 at `start`: c = 0.5 / start^2 there, times the peak's height).
class PeakRefiner {
 public:
  PeakRefiner(const std::vector<double>& r, Eigen::Index start, Eigen::Index best)
      : r_(r), max_lag_(static_cast<Eigen::Index>(r.size()) - 1) {
    std::vector<double> third;
    for (Eigen::Index m = start; m + 3 <= max_lag_; ++m) {
      third.push_back(std::abs(r[m + 3] - 3.0 * r[m + 2] + 3.0 * r[m + 1] - r[m]));
    }
    double white = 0;
    if (!third.empty()) {
      std::nth_element(third.begin(), third.begin() + third.size() / 2, third.end());
      white = third[third.size() / 2] / 0.6745 / std::sqrt(20.0);  // median |N(0, s)| = 0.6745 s
    }
    const double curvature = 0.5 * r[best] / (static_cast<double>(start) * start);
    const double ratio = white / (2.0 * curvature * 0.01);
    half_width_ = std::clamp<Eigen::Index>(
        static_cast<Eigen::Index>(std::ceil(std::cbrt(1.5 * ratio * ratio))), 1,
        std::max<Eigen::Index>(1, start / 4));
  }

  // The vertex of the parabola around lag m, within the window.
  double operator()(Eigen::Index m) const {
    const std::vector<double>& r = r_;
    const Eigen::Index w = std::min({half_width_, m, max_lag_ - m});
    if (w < 1) return static_cast<double>(m);
    // r = p0 + p1 d + p2 d^2 on d = -w..w: odd sums vanish.
    double s2 = 0, s4 = 0, r0 = 0, r1 = 0, r2 = 0;
    for (Eigen::Index d = -w; d <= w; ++d) {
      const double dd = static_cast<double>(d), v = r[m + d];
      s2 += dd * dd;
      s4 += dd * dd * dd * dd;
      r0 += v;
      r1 += dd * v;
      r2 += dd * dd * v;
    }
    const double count = static_cast<double>(2 * w + 1);
    const double p2 = (count * r2 - s2 * r0) / (count * s4 - s2 * s2);
    const double p1 = r1 / s2;
    if (!(p2 < 0)) return static_cast<double>(m);
    return static_cast<double>(m) +
           std::clamp(-p1 / (2.0 * p2), -static_cast<double>(w), static_cast<double>(w));
  }

 private:
  const std::vector<double>& r_;
  const Eigen::Index max_lag_;
  Eigen::Index half_width_ = 1;
};

}  // namespace

double detect_period(const Trajectory& x) {
  const double dt = uniform_sample_time(x);
  check_shapes(x, false);
  check_finite(x, x.q, "q");
  const Eigen::Index n = x.t.size();
  if (n < 8) fail(x, "fewer than 8 samples to find a period in");
  // Lags up to 3/4 of the record: a quarter still overlaps, enough to see a period longer
  // than half the record and say that fewer than 2 periods were recorded.
  const Eigen::Index max_lag = n - n / 4;
  const std::vector<double> r = lag_correlation(x, max_lag);
  const Eigen::Index start = end_of_first_lobe(x, r);
  const Eigen::Index best = highest_correlation(x, r, start, dt);
  // Every multiple of the period correlates about as well as the best; noise lowers them all
  // alike. The period is the first run of lags that high, at its maximum.
  const double threshold = r[best] - (1e-3 + 0.5 * (1.0 - r[best]));
  const PeakRefiner refine(r, start, best);
  Eigen::Index first = start;
  while (r[first] < threshold) ++first;
  Eigen::Index last = first;
  while (last < max_lag && r[last + 1] >= threshold) ++last;
  const Eigen::Index peak = peak_near(r, first, last);
  // The peaks at the multiples k T of the period, m_k = k T: least squares through the
  // origin, T = sum k m_k / sum k^2, dominated by the farthest multiples.
  double lag = refine(peak), moment = lag, weight = 1;
  for (int multiple = 2;; ++multiple) {
    const auto centre = static_cast<Eigen::Index>(std::llround(multiple * lag));
    if (centre + 3 > max_lag) break;
    const Eigen::Index at = peak_near(r, centre - 2, centre + 2);
    if (r[at] < threshold) break;
    moment += multiple * refine(at);
    weight += static_cast<double>(multiple) * multiple;
    lag = moment / weight;
  }
  const double period = lag * dt;
  if (2.0 * lag > static_cast<double>(n) + 0.5) {
    fail(x, "the positions seem to repeat with a period of " + format(period) + " s (correlation " +
                format(r[peak]) + ") but the record is " + format(static_cast<double>(n) * dt) +
                " s long (" + format(static_cast<double>(n) / lag) +
                " periods); averaging needs at least 2 periods");
  }
  return period;
}

PeriodicAverage average_periods(const Trajectory& x, double period) {
  const double dt = uniform_sample_time(x);
  check_shapes(x, true);
  check_finite(x, x.q, "q");
  check_finite(x, x.tau, "tau");
  if (x.has_velocity) {
    check_finite(x, x.dq, "dq");
    check_finite(x, x.ddq, "ddq");
  }
  if (!(period > 0) || !std::isfinite(period)) {
    fail(x, "the period must be positive and finite, got " + format(period) + " s");
  }
  const Eigen::Index n = x.t.size(), dof = x.q.cols();
  const double ratio = period / dt;
  if (ratio > static_cast<double>(n)) {
    fail(x, "the record (" + std::to_string(n) + " samples, " +
                format(static_cast<double>(n) * dt) + " s) is shorter than one period of " +
                format(period) + " s; averaging needs at least 2 whole periods");
  }
  const Eigen::Index samples = std::llround(ratio);
  if (samples < 2) {
    fail(x, "the period " + format(period) + " s is shorter than 2 samples (dt = " + format(dt) +
                " s)");
  }
  const Eigen::Index periods = n / samples;
  if (periods < 2) {
    fail(x, "only " + format(static_cast<double>(n) / ratio) + " periods of " + format(period) +
                " s are recorded (" + std::to_string(n) + " samples, " + std::to_string(samples) +
                " per period); averaging needs at least 2 whole periods");
  }
  // A period off the sample grid shifts period p by p (ratio - N) samples.
  const double misalignment = std::abs(ratio - static_cast<double>(samples)) * periods;
  if (misalignment > 0.25) {
    fail(x, "the period " + format(period) + " s is not a whole number of samples: period / dt = " +
                format(ratio) + " with dt = " + format(dt) + " s, so the " +
                std::to_string(periods) + " periods would be misaligned by up to " +
                format(misalignment) + " samples (at most 0.25 allowed); the nearest whole " +
                "period is " + format(static_cast<double>(samples) * dt) + " s");
  }

  PeriodicAverage out;
  out.periods = static_cast<int>(periods);
  out.samples_per_period = samples;
  out.period = static_cast<double>(samples) * dt;
  out.dropped_samples = n - periods * samples;
  out.dropped_seconds = static_cast<double>(out.dropped_samples) * dt;
  Trajectory& avg = out.averaged;
  avg.source = x.source;
  avg.t = x.t.head(samples);
  avg.has_velocity = x.has_velocity;
  const double p = static_cast<double>(periods);
  // Mean over the periods of each sample of the period, and the sum of squared deviations.
  auto average = [&](const Eigen::MatrixXd& in, Eigen::MatrixXd& mean, Eigen::VectorXd* var) {
    mean = Eigen::MatrixXd::Zero(samples, dof);
    for (Eigen::Index i = 0; i < periods; ++i) mean += in.middleRows(i * samples, samples);
    mean /= p;
    if (var == nullptr) return;
    var->resize(dof);
    for (Eigen::Index j = 0; j < dof; ++j) {
      double squares = 0;
      for (Eigen::Index i = 0; i < periods; ++i) {
        squares += (in.col(j).segment(i * samples, samples) - mean.col(j)).squaredNorm();
      }
      // Swevers 2002, after Figure 5: sample variance over the periods, divided by P. The
      // N (P - 1) degrees of freedom make it unbiased.
      (*var)[j] = squares / (static_cast<double>(samples) * (p - 1.0)) / p;
    }
  };
  average(x.q, avg.q, &out.q_noise_variance);
  average(x.tau, avg.tau, &out.tau_noise_variance);
  // The same spread line by line: the DFT of each period's deviation from the mean, and the
  // products of the torque's and the position's lines for their cross-covariance.
  const Eigen::Index half = samples / 2;
  out.q_line_variance.setZero(half + 1, dof);
  out.tau_line_variance.setZero(half + 1, dof);
  out.tau_q_line_covariance.setZero(half + 1, dof);
  for (Eigen::Index j = 0; j < dof; ++j) {
    for (Eigen::Index i = 0; i < periods; ++i) {
      const std::vector<std::complex<double>> dq =
          detail::dft(x.q.col(j).segment(i * samples, samples) - avg.q.col(j));
      const std::vector<std::complex<double>> dtau =
          detail::dft(x.tau.col(j).segment(i * samples, samples) - avg.tau.col(j));
      for (Eigen::Index l = 0; l <= half; ++l) {
        out.q_line_variance(l, j) += std::norm(dq[l]);
        out.tau_line_variance(l, j) += std::norm(dtau[l]);
        out.tau_q_line_covariance(l, j) += dtau[l] * std::conj(dq[l]);
      }
    }
  }
  const double pairs = p * (p - 1.0);
  out.q_line_variance /= pairs;
  out.tau_line_variance /= pairs;
  out.tau_q_line_covariance /= pairs;
  if (x.has_velocity) {
    average(x.dq, avg.dq, nullptr);
    average(x.ddq, avg.ddq, nullptr);
  } else {
    avg.dq = Eigen::MatrixXd::Zero(samples, dof);
    avg.ddq = Eigen::MatrixXd::Zero(samples, dof);
  }
  return out;
}

}  // namespace modelgen
