// Velocities and accelerations by central differences on any time grid, of the positions as
// they are or low-passed without phase shift first (Gautier & Briot, section IV.A).

#include "modelgen/signal/differentiation.hpp"

#include <string>

#include "modelgen/signal/lowpass.hpp"
#include "modelgen/signal/sampling.hpp"
#include "runtime/src/signal/trajectory_checks.hpp"

namespace modelgen {

namespace {

using detail::check_finite;
using detail::check_shapes;
using detail::fail;
using detail::format;

}  // namespace

void differentiate(Trajectory& x) {
  const Eigen::Index n = x.t.size();
  if (n < 3) throw DataError(x.source + ": error: fewer than 3 samples to differentiate");
  const Eigen::Index dof = x.q.cols();
  Eigen::MatrixXd dq(n - 2, dof), ddq(n - 2, dof);
  for (Eigen::Index s = 1; s + 1 < n; ++s) {
    const double h0 = x.t[s] - x.t[s - 1], h1 = x.t[s + 1] - x.t[s];
    for (Eigen::Index j = 0; j < dof; ++j) {
      const double a = x.q(s - 1, j), b = x.q(s, j), c = x.q(s + 1, j);
      // Second-order differences on a non-uniform grid.
      dq(s - 1, j) =
          (-h1 / (h0 * (h0 + h1))) * a + ((h1 - h0) / (h0 * h1)) * b + (h0 / (h1 * (h0 + h1))) * c;
      ddq(s - 1, j) = 2.0 * (a / (h0 * (h0 + h1)) - b / (h0 * h1) + c / (h1 * (h0 + h1)));
    }
  }
  x.t = x.t.segment(1, n - 2).eval();
  x.q = x.q.middleRows(1, n - 2).eval();
  x.tau = x.tau.middleRows(1, n - 2).eval();
  x.dq = dq;
  x.ddq = ddq;
  x.has_velocity = true;
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

}  // namespace modelgen
