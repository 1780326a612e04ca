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

}  // namespace

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

}  // namespace modelgen
