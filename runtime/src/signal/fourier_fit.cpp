// Fourier re-estimation of one averaged period (Swevers et al. 2002, eq. 15-17 and section 4):
// how many harmonics stand out of the noise, their coefficients by the DFT, and the analytic
// positions, velocities and accelerations they give.

#include "modelgen/signal/fourier_fit.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "modelgen/signal/sampling.hpp"
#include "runtime/src/signal/dft.hpp"
#include "runtime/src/signal/trajectory_checks.hpp"

namespace modelgen {

namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;
using detail::check_finite;
using detail::check_shapes;
using detail::dft;
using detail::fail;
using detail::format;

// Lines above this many times their noise variance are signal: exp(-25) = 1.4e-11 under noise.
constexpr double kLineSignificance = 25.0;
// The noise variance of a line: the mean over this many lines on either side (one line's
// variance from P periods has only 2 (P - 1) degrees of freedom), then the largest such mean
// within as many lines, so that a narrow peak of coloured noise is not averaged away.
constexpr Eigen::Index kVarianceLines = 2;

// The highest line 1..max_line of any column of x (one period) whose power stands out of its
// line noise variance (rows 0..N/2 of `variance`), and of round-off (1e-18 of the largest line
// power, as the per-axis rule's 1e-9 of the largest amplitude); 0 when none does.
Eigen::Index highest_significant_line(const Eigen::MatrixXd& x, const Eigen::MatrixXd& variance,
                                      Eigen::Index max_line) {
  Eigen::Index highest = 0;
  const Eigen::Index last = variance.rows() - 1;
  std::vector<std::vector<Complex>> spectra;
  double largest = 0;
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    spectra.push_back(dft(x.col(j)));
    for (Eigen::Index l = 1; l <= max_line; ++l) largest = std::max(largest, std::norm(spectra[j][l]));
  }
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    Eigen::VectorXd mean(last + 1);
    for (Eigen::Index l = 0; l <= last; ++l) {
      const Eigen::Index from = std::max<Eigen::Index>(1, l - kVarianceLines);
      const Eigen::Index to = std::max(from, std::min(last, l + kVarianceLines));
      mean[l] = variance.col(j).segment(from, to - from + 1).mean();
    }
    for (Eigen::Index l = max_line; l > highest; --l) {
      const Eigen::Index from = std::max<Eigen::Index>(1, l - kVarianceLines);
      const Eigen::Index to = std::min(last, l + kVarianceLines);
      const double noise = mean.segment(from, to - from + 1).maxCoeff();
      if (std::norm(spectra[j][l]) > std::max(kLineSignificance * noise, 1e-18 * largest)) {
        highest = l;
        break;
      }
    }
  }
  return highest;
}

}  // namespace

int select_torque_harmonics(const PeriodicAverage& average, int position_harmonics) {
  const Trajectory& x = average.averaged;
  const Eigen::Index n = x.tau.rows();
  const Eigen::Index max_harmonics = (n - 1) / 2;
  if (average.tau_line_variance.rows() != n / 2 + 1 ||
      average.tau_line_variance.cols() != x.tau.cols()) {
    return position_harmonics;
  }
  check_finite(x, x.tau, "tau");
  return static_cast<int>(std::max<Eigen::Index>(
      position_harmonics, highest_significant_line(x.tau, average.tau_line_variance, max_harmonics)));
}

void keep_harmonics(Trajectory& one_period, Eigen::MatrixXd& columns, int harmonics) {
  const Eigen::Index n = columns.rows();
  if (harmonics < 0 || 2 * static_cast<Eigen::Index>(harmonics) >= n) {
    fail(one_period, "cannot keep " + std::to_string(harmonics) + " harmonics of " +
                         std::to_string(n) + " samples per period");
  }
  for (Eigen::Index j = 0; j < columns.cols(); ++j) {
    const std::vector<Complex> spectrum = dft(columns.col(j));
    for (Eigen::Index k = 0; k < n; ++k) {
      double value = spectrum[0].real();
      for (int l = 1; l <= harmonics; ++l) {
        value += 2.0 * (spectrum[l] * std::polar(1.0, 2.0 * kPi * l * static_cast<double>(k) /
                                                          static_cast<double>(n)))
                           .real();
      }
      columns(k, j) = value / static_cast<double>(n);
    }
  }
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
  if (average.q_line_variance.rows() == n / 2 + 1 && average.q_line_variance.cols() == dof) {
    return static_cast<int>(std::max<Eigen::Index>(
        1, highest_significant_line(x.q, average.q_line_variance, max_harmonics)));
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

}  // namespace modelgen
