// The noise variances of the prepared period from the per-line variances of the average (the
// derivation is in the header).

#include "modelgen/signal/periodic_noise.hpp"

#include <algorithm>
#include <numbers>

namespace modelgen {

PeriodicNoise periodic_noise(const PeriodicAverage& average, int harmonics, int torque_harmonics) {
  const Eigen::MatrixXd& v = average.q_line_variance;
  const Eigen::Index dof = v.cols(), lines = v.rows();
  const double N = static_cast<double>(average.samples_per_period);
  const double w = 2.0 * std::numbers::pi / average.period;
  const Eigen::Index H = std::min<Eigen::Index>(harmonics, lines - 1);
  PeriodicNoise out;
  out.samples = average.samples_per_period;
  out.period = average.period;
  out.periods = average.periods;
  out.q_lines = v.topRows(H + 1);
  out.q = v.row(0).transpose();
  out.dq = out.ddq = out.q_ddq = Eigen::VectorXd::Zero(dof);
  for (Eigen::Index l = 1; l <= H; ++l) {
    const double wl2 = (w * l) * (w * l);
    out.q += 2.0 * v.row(l).transpose();
    out.dq += 2.0 * wl2 * v.row(l).transpose();
    out.ddq += 2.0 * wl2 * wl2 * v.row(l).transpose();
    out.q_ddq -= 2.0 * wl2 * v.row(l).transpose();
  }
  const double n2 = N * N;
  out.q /= n2;
  out.dq /= n2;
  out.ddq /= n2;
  out.q_ddq /= n2;
  if (torque_harmonics < 0) {
    out.tau = average.tau_noise_variance;
  } else {
    const Eigen::MatrixXd& vt = average.tau_line_variance;
    const Eigen::Index Ht = std::min<Eigen::Index>(torque_harmonics, vt.rows() - 1);
    out.tau_lines = vt.topRows(Ht + 1);
    out.tau = vt.row(0).transpose();
    for (Eigen::Index l = 1; l <= Ht; ++l) out.tau += 2.0 * vt.row(l).transpose();
    out.tau /= n2;
  }
  return out;
}

}  // namespace modelgen
