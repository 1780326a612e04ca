// Data preparation: period detection, averaging and noise variance, DFT re-estimation of the
// Fourier coefficients (Swevers et al. 2002, eq. 15-17 and section 4); Butterworth and
// Chebyshev I low-pass design by the bilinear transform, zero-phase filtering, central
// differences of filtered positions and parallel decimation (Gautier & Briot eq. 13-14).

#include "modelgen/preprocess.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <unsupported/Eigen/FFT>

namespace modelgen {

namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;

std::string format(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

std::string name_of(const Trajectory& x) { return x.source.empty() ? "trajectory" : x.source; }

[[noreturn]] void fail(const Trajectory& x, const std::string& message) {
  throw DataError(name_of(x) + ": error: " + message);
}

// Every matrix has one row per time and q, tau (when `torque`) and dq, ddq (when present) the
// same columns.
void check_shapes(const Trajectory& x, bool torque) {
  const Eigen::Index n = x.t.size(), dof = x.q.cols();
  auto check = [&](const Eigen::MatrixXd& m, const char* name) {
    if (m.rows() != n || m.cols() != dof) {
      fail(x, std::string(name) + " is " + std::to_string(m.rows()) + " x " +
                  std::to_string(m.cols()) + ", expected " + std::to_string(n) + " x " +
                  std::to_string(dof) + " (samples x axes)");
    }
  };
  check(x.q, "q");
  if (torque) check(x.tau, "tau");
  if (x.has_velocity) {
    check(x.dq, "dq");
    check(x.ddq, "ddq");
  }
}

// The first non-finite entry of `m` (samples x axes) is reported as sample, time and column.
void check_finite(const Trajectory& x, const Eigen::MatrixXd& m, const char* prefix) {
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index s = 0; s < m.rows(); ++s) {
      if (!std::isfinite(m(s, j))) {
        fail(x, "sample " + std::to_string(s + 1) + " (t = " + format(x.t[s]) + " s), column '" +
                    prefix + std::to_string(j + 1) + "' is NaN or infinite; data must be finite");
      }
    }
  }
}

Eigen::Index next_power_of_two(Eigen::Index n) {
  Eigen::Index m = 1;
  while (m < n) m *= 2;
  return m;
}

// Discrete Fourier transform X_l = sum_k x_k exp(-2 pi i l k / n) of any length, by
// Bluestein's chirp: l k = (l^2 + k^2 - (l - k)^2) / 2 turns the DFT into a convolution, done
// with power-of-two FFTs, so the cost is O(n log n) even for prime n.
std::vector<Complex> dft(const Eigen::Ref<const Eigen::VectorXd>& x) {
  const Eigen::Index n = x.size();
  Eigen::FFT<double> fft;
  std::vector<Complex> in(x.data(), x.data() + n), out;
  if (n == next_power_of_two(n)) {
    fft.fwd(out, in);
    return out;
  }
  const Eigen::Index m = next_power_of_two(2 * n - 1);
  // w_k = exp(-i pi k^2 / n); k^2 mod 2n in integers keeps the angle exact for large k.
  std::vector<Complex> w(n);
  const std::uint64_t two_n = 2 * static_cast<std::uint64_t>(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const std::uint64_t kk = static_cast<std::uint64_t>(k) * static_cast<std::uint64_t>(k);
    w[k] = std::polar(1.0, -kPi * static_cast<double>(kk % two_n) / static_cast<double>(n));
  }
  std::vector<Complex> a(m, 0.0), b(m, 0.0), fa, fb;
  for (Eigen::Index k = 0; k < n; ++k) a[k] = in[k] * w[k];
  b[0] = std::conj(w[0]);
  for (Eigen::Index k = 1; k < n; ++k) b[k] = b[m - k] = std::conj(w[k]);
  fft.fwd(fa, a);
  fft.fwd(fb, b);
  for (Eigen::Index k = 0; k < m; ++k) fa[k] *= fb[k];
  fft.inv(a, fa);
  out.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) out[k] = w[k] * a[k];
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Sampling

double uniform_sample_time(const Trajectory& x) {
  const Eigen::Index n = x.t.size();
  if (n < 2) fail(x, "fewer than 2 samples");
  for (Eigen::Index k = 0; k < n; ++k) {
    if (!std::isfinite(x.t[k])) {
      fail(x, "sample " + std::to_string(k + 1) + ", column 't' is NaN or infinite");
    }
  }
  const double dt = (x.t[n - 1] - x.t[0]) / static_cast<double>(n - 1);
  if (!(dt > 0)) fail(x, "time does not increase from the first to the last sample");
  for (Eigen::Index k = 0; k < n; ++k) {
    const double off = (x.t[k] - (x.t[0] + static_cast<double>(k) * dt)) / dt;
    if (std::abs(off) > 0.01) {
      fail(x, "sampling is not uniform: sample " + std::to_string(k + 1) +
                  " (t = " + format(x.t[k]) + " s) is " + format(off) +
                  " samples off the grid t1 + k dt with dt = " + format(dt) +
                  " s (at most 0.01 allowed); resample the data first");
    }
  }
  return dt;
}

// ---------------------------------------------------------------------------------------------
// Periodic excitation

double detect_period(const Trajectory& x) {
  constexpr double kMinCorrelation = 0.9, kDecorrelated = 0.5;
  const double dt = uniform_sample_time(x);
  check_shapes(x, false);
  check_finite(x, x.q, "q");
  const Eigen::Index n = x.t.size(), dof = x.q.cols();
  if (n < 8) fail(x, "fewer than 8 samples to find a period in");
  // Lags up to 3/4 of the record: a quarter still overlaps, enough to see a period longer
  // than half the record and say that fewer than 2 periods were recorded.
  const Eigen::Index max_lag = n - n / 4;

  // Pooled Pearson correlation of q(k) with q(k + m) over the overlap, per lag m:
  // r(m) = sum_j cov_j(m) / sum_j sqrt(var_a_j(m) var_b_j(m)), segment means removed, so each
  // axis counts with its position variance. The lagged products come from one FFT per axis.
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

  // Skip the lobe around lag 0 (down to a clear decorrelation, so that a small vibration on a
  // slow motion is not taken for a period), then take the highest correlation.
  Eigen::Index start = 1;
  while (start <= max_lag && r[start] >= kDecorrelated) ++start;
  if (start > max_lag) {
    fail(x,
         "no period found: the positions never decorrelate over the record (a drift or a "
         "motion slower than the record)");
  }
  Eigen::Index best = start;
  for (Eigen::Index m = start; m <= max_lag; ++m) {
    if (r[m] > r[best]) best = m;
  }
  if (r[best] < kMinCorrelation) {
    fail(x, "no period found: the positions never correlate with themselves again above " +
                format(kMinCorrelation) + " (best " + format(r[best]) + " at a lag of " +
                format(static_cast<double>(best) * dt) + " s)");
  }
  // Every multiple of the period correlates about as well as the best; noise lowers them all
  // alike. The period is the first run of lags that high, at its maximum.
  const double threshold = r[best] - (1e-3 + 0.5 * (1.0 - r[best]));
  auto peak_near = [&](Eigen::Index from, Eigen::Index to) {
    Eigen::Index at = from;
    for (Eigen::Index m = from; m <= to; ++m) {
      if (r[m] > r[at]) at = m;
    }
    return at;
  };
  // Sub-sample position of a peak: least-squares parabola over the lags d = -w..w around it.
  // r is a smooth function of the lag plus a part that is white from lag to lag (noise
  // correlated with noise), which more lags average out; but the peak is slightly asymmetric
  // (the overlap shrinks as the lag grows), which biases wider fits. So w is the smallest
  // window that brings the vertex's noise to 0.01 sample: its standard deviation is about
  // s / (2 |c| sqrt(2 w^3 / 3)) for white noise s on r and curvature c, with s estimated from
  // third differences of r (variance 20 s^2 for white noise) and c from the lag-0 lobe
  // (r drops to 0.5 at `start`: c = 0.5 / start^2 there, times the peak's height).
  std::vector<double> third;
  for (Eigen::Index m = start; m + 3 <= max_lag; ++m) {
    third.push_back(std::abs(r[m + 3] - 3.0 * r[m + 2] + 3.0 * r[m + 1] - r[m]));
  }
  double white = 0;
  if (!third.empty()) {
    std::nth_element(third.begin(), third.begin() + third.size() / 2, third.end());
    white = third[third.size() / 2] / 0.6745 / std::sqrt(20.0);  // median |N(0, s)| = 0.6745 s
  }
  const double curvature = 0.5 * r[best] / (static_cast<double>(start) * start);
  const double ratio = white / (2.0 * curvature * 0.01);
  const Eigen::Index half_width =
      std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::ceil(std::cbrt(1.5 * ratio * ratio))),
                               1, std::max<Eigen::Index>(1, start / 4));
  auto refine = [&](Eigen::Index m) {
    const Eigen::Index w = std::min({half_width, m, max_lag - m});
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
  };
  Eigen::Index first = start;
  while (r[first] < threshold) ++first;
  Eigen::Index last = first;
  while (last < max_lag && r[last + 1] >= threshold) ++last;
  const Eigen::Index peak = peak_near(first, last);
  // The peaks at the multiples k T of the period, m_k = k T: least squares through the
  // origin, T = sum k m_k / sum k^2, dominated by the farthest multiples.
  double lag = refine(peak), moment = lag, weight = 1;
  for (int multiple = 2;; ++multiple) {
    const auto centre = static_cast<Eigen::Index>(std::llround(multiple * lag));
    if (centre + 3 > max_lag) break;
    const Eigen::Index at = peak_near(centre - 2, centre + 2);
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
  if (x.has_velocity) {
    average(x.dq, avg.dq, nullptr);
    average(x.ddq, avg.ddq, nullptr);
  } else {
    avg.dq = Eigen::MatrixXd::Zero(samples, dof);
    avg.ddq = Eigen::MatrixXd::Zero(samples, dof);
  }
  return out;
}

int select_harmonics(const PeriodicAverage& average) {
  const Trajectory& x = average.averaged;
  const Eigen::Index n = x.q.rows(), dof = x.q.cols();
  if (average.q_noise_variance.size() != dof) {
    fail(x, "the position noise variance has " + std::to_string(average.q_noise_variance.size()) +
                " entries for " + std::to_string(dof) + " axes");
  }
  const Eigen::Index max_harmonics = (n - 1) / 2;
  if (max_harmonics < 1) {
    fail(x, std::to_string(n) + " samples per period leave no room for a harmonic");
  }
  check_finite(x, x.q, "q");
  // Amplitudes |c_jl| = 2 |X_jl| / N of harmonics 1..max_harmonics, per axis.
  Eigen::MatrixXd amplitude(max_harmonics, dof);
  for (Eigen::Index j = 0; j < dof; ++j) {
    const std::vector<Complex> spectrum = dft(x.q.col(j));
    for (Eigen::Index l = 1; l <= max_harmonics; ++l) {
      amplitude(l - 1, j) = 2.0 * std::abs(spectrum[l]) / static_cast<double>(n);
    }
  }
  const double floor = 1e-9 * amplitude.maxCoeff();
  Eigen::Index harmonics = 1;
  for (Eigen::Index j = 0; j < dof; ++j) {
    // White noise of variance v on N samples puts N v / 2 on the real and imaginary part of
    // each DFT line, so 2 v / N on each part of c_jl.
    const double noise =
        std::sqrt(2.0 * std::max(average.q_noise_variance[j], 0.0) / static_cast<double>(n));
    const double threshold = std::max(6.0 * noise, floor);
    for (Eigen::Index l = max_harmonics; l > harmonics; --l) {
      if (amplitude(l - 1, j) > threshold) {
        harmonics = l;
        break;
      }
    }
  }
  return static_cast<int>(harmonics);
}

FourierTrajectory fit_fourier(const Trajectory& x, double period, int harmonics) {
  const double dt = uniform_sample_time(x);
  if (x.q.rows() != x.t.size()) {
    fail(x, "q has " + std::to_string(x.q.rows()) + " rows for " + std::to_string(x.t.size()) +
                " times");
  }
  check_finite(x, x.q, "q");
  const Eigen::Index n = x.t.size(), dof = x.q.cols();
  if (!(period > 0) || std::abs(static_cast<double>(n) * dt - period) > 0.05 * dt) {
    fail(x, "expected one period of " + format(period) + " s, but the " + std::to_string(n) +
                " samples span " + format(static_cast<double>(n) * dt) +
                " s (N dt, dt = " + format(dt) + " s)");
  }
  if (harmonics < 1 || 2 * static_cast<Eigen::Index>(harmonics) >= n) {
    fail(x, "cannot estimate " + std::to_string(harmonics) + " harmonics from " +
                std::to_string(n) + " samples per period: between 1 and " +
                std::to_string((n - 1) / 2) + " (below the Nyquist frequency)");
  }
  FourierTrajectory f;
  f.period = period;
  f.q0.resize(dof);
  f.a.resize(dof, harmonics);
  f.b.resize(dof, harmonics);
  const double wf = 2.0 * kPi / period;
  const double t0 = x.t[0];
  const double scale = 2.0 / static_cast<double>(n);
  for (Eigen::Index j = 0; j < dof; ++j) {
    const std::vector<Complex> spectrum = dft(x.q.col(j));
    f.q0[j] = spectrum[0].real() / static_cast<double>(n);
    for (int l = 1; l <= harmonics; ++l) {
      const double w = wf * l;
      // Sample k is at t0 + k period / N, so line l of the DFT is (N / 2) C exp(i l wf t0)
      // for the component Re(C exp(i l wf t)) = B cos + A sin, C = B - i A. Eq. 15:
      // A = a / (l wf), B = -b / (l wf).
      const Complex c = scale * spectrum[l] * std::polar(1.0, -w * t0);
      f.a(j, l - 1) = -c.imag() * w;
      f.b(j, l - 1) = -c.real() * w;
    }
  }
  return f;
}

void apply_fourier(Trajectory& x, const FourierTrajectory& f) {
  const Eigen::Index n = x.t.size(), dof = x.q.cols();
  if (f.q0.size() != dof || f.a.rows() != dof || f.b.rows() != dof || f.a.cols() != f.b.cols()) {
    fail(x, "the Fourier trajectory has " + std::to_string(f.q0.size()) + " offsets and " +
                std::to_string(f.a.rows()) + " x " + std::to_string(f.a.cols()) + " and " +
                std::to_string(f.b.rows()) + " x " + std::to_string(f.b.cols()) +
                " coefficients for " + std::to_string(dof) + " axes");
  }
  if (!(f.period > 0)) fail(x, "the Fourier trajectory's period must be positive");
  x.q.resize(n, dof);
  x.dq.resize(n, dof);
  x.ddq.resize(n, dof);
  Eigen::VectorXd q, dq, ddq;
  for (Eigen::Index s = 0; s < n; ++s) {
    // Swevers 2002, eq. 15-17.
    f.evaluate(x.t[s], q, dq, ddq);
    x.q.row(s) = q;
    x.dq.row(s) = dq;
    x.ddq.row(s) = ddq;
  }
  x.has_velocity = true;
}

// ---------------------------------------------------------------------------------------------
// Low-pass filters

namespace {

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

// Samples over which the slowest pole decays by e^-10: how long a start-up transient lasts.
Eigen::Index settling_samples(const LowPassFilter& filter) {
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

// Group delay at DC, in samples, of one section: sum k b_k / sum b_k - sum k a_k / sum a_k.
double dc_delay(const LowPassFilter::Section& s) {
  return (s.b1 + 2.0 * s.b2) / (s.b0 + s.b1 + s.b2) - (s.a1 + 2.0 * s.a2) / (1.0 + s.a1 + s.a2);
}

// One pass of the cascade over u[0..len) (backward: from the end), transposed direct form II.
// It starts in the steady state of the ramp through its first two values, as if the input had
// always been that ramp: a unit-DC-gain section answers v0 + d k with v0 + d (k - D), D its DC
// delay, and its two states then hold what the past of that ramp left in them. A linear input
// passes without any start-up transient.
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

// Zero-phase filtering of one column (any stride) into `buffer` (odd-reflection padded, see
// filtfilt); returns the offset of the first original sample in the buffer.
template <typename Column>
Eigen::Index filtfilt_column(const LowPassFilter& filter, const Column& x, Eigen::Index settling,
                             std::vector<double>& buffer, std::vector<double>& state) {
  const Eigen::Index n = x.size();
  const Eigen::Index pad = std::min(n - 1, settling);
  buffer.resize(n + 2 * pad);
  double* u = buffer.data();
  for (Eigen::Index k = 0; k < n; ++k) u[pad + k] = x(k);
  for (Eigen::Index i = 1; i <= pad; ++i) {
    u[pad - i] = 2.0 * x(0) - x(i);
    u[pad + n - 1 + i] = 2.0 * x(n - 1) - x(n - 1 - i);
  }
  const auto len = static_cast<Eigen::Index>(buffer.size());
  run_sections(filter, u, len, false, state);
  run_sections(filter, u, len, true, state);
  return pad;
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

void filter_positions(Trajectory& x, double cutoff_hz, int order) {
  const double dt = uniform_sample_time(x);
  check_shapes(x, true);
  check_finite(x, x.q, "q");
  if (x.t.size() < 3) fail(x, "fewer than 3 samples to filter and differentiate");
  const double rate = 1.0 / dt;
  if (!(cutoff_hz > 0) || !(cutoff_hz < rate / 2)) {
    fail(x, "position filter cut-off " + format(cutoff_hz) +
                " Hz is not between 0 and the Nyquist frequency " + format(rate / 2) +
                " Hz of the data (sample rate " + format(rate) + " Hz)");
  }
  // Gautier & Briot, section IV.A: q filtered without phase shift, then differentiated.
  filtfilt(butterworth_lowpass(order, cutoff_hz, rate), x.q);
  differentiate(x);
}

// ---------------------------------------------------------------------------------------------
// Parallel decimation

LowPassFilter decimation_filter(int factor) {
  if (factor < 2) {
    throw std::invalid_argument("decimation factor must be at least 2 for a filter, got " +
                                std::to_string(factor));
  }
  // Matlab's decimate: cheby1(8, 0.05, 0.8 / r), cut-off relative to Nyquist (0.5 here).
  return chebyshev1_lowpass(8, 0.05, 0.4 / factor, 1.0);
}

Eigen::Index decimated_rows(Eigen::Index rows, int factor) {
  if (factor < 1) {
    throw std::invalid_argument("decimation factor must be at least 1, got " +
                                std::to_string(factor));
  }
  return rows == 0 ? 0 : (rows - 1) / factor + 1;
}

void decimate(const ConstStridedMatrixRef& x, int factor, StridedMatrixRef out) {
  const Eigen::Index n = x.rows(), rows = decimated_rows(n, factor);
  if (out.rows() != rows || out.cols() != x.cols()) {
    throw std::invalid_argument("decimate: output is " + std::to_string(out.rows()) + " x " +
                                std::to_string(out.cols()) + ", expected " + std::to_string(rows) +
                                " x " + std::to_string(x.cols()) + " (" + std::to_string(n) +
                                " rows decimated by " + std::to_string(factor) + ")");
  }
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    for (Eigen::Index s = 0; s < n; ++s) {
      if (!std::isfinite(x(s, c))) {
        throw std::invalid_argument("decimate: row " + std::to_string(s + 1) + ", column " +
                                    std::to_string(c + 1) + " is NaN or infinite");
      }
    }
  }
  if (factor == 1) {
    out = x;
    return;
  }
  if (n == 0) return;
  const LowPassFilter filter = decimation_filter(factor);
  const Eigen::Index settling = settling_samples(filter);
  std::vector<double> buffer, state;
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    // Gautier & Briot eq. 13-14: the same low-pass on every column, then one row in n_d.
    const Eigen::Index pad = filtfilt_column(filter, x.col(c), settling, buffer, state);
    for (Eigen::Index i = 0; i < rows; ++i) out(i, c) = buffer[pad + i * factor];
  }
}

Eigen::MatrixXd decimate(const ConstStridedMatrixRef& x, int factor) {
  Eigen::MatrixXd out(decimated_rows(x.rows(), factor), x.cols());
  decimate(x, factor, out);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Choosing the cut-off and the decimation factor

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
