// Fourier excitation (Swevers et al. 2002, eq. 15-17).

#include "modelgen/excitation/fourier_trajectory.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace modelgen {

// The sine and cosine of each harmonic once for all joints (the cost per instant: L of each and
// 10 dof L flops). Each joint's terms are the same expressions added in the same order as term
// by term, so the values are the same to the bit: the bundled data sets are reproducible.
void FourierTrajectory::evaluate(double t, Eigen::VectorXd& q, Eigen::VectorXd& dq,
                                 Eigen::VectorXd& ddq) const {
  const double wf = 2.0 * std::numbers::pi / period;
  const Eigen::Index dof = q0.size();
  q = q0;
  dq = Eigen::VectorXd::Zero(dof);
  ddq = Eigen::VectorXd::Zero(dof);
  for (Eigen::Index l = 0; l < a.cols(); ++l) {
    const double w = wf * static_cast<double>(l + 1);
    const double s = std::sin(w * t), c = std::cos(w * t);
    // Swevers eq. 15-17 with velocity amplitudes (a, b).
    for (Eigen::Index j = 0; j < dof; ++j) {
      q[j] += a(j, l) / w * s - b(j, l) / w * c;
      dq[j] += a(j, l) * c + b(j, l) * s;
      ddq[j] += -a(j, l) * w * s + b(j, l) * w * c;
    }
  }
}

Trajectory sample(const FourierTrajectory& trajectory, double sample_time, double duration) {
  const Eigen::Index joints = trajectory.q0.size();
  if (trajectory.a.rows() != joints || trajectory.b.rows() != joints ||
      trajectory.a.cols() != trajectory.b.cols()) {
    throw std::invalid_argument(
        "Fourier coefficients a and b need one row per joint and equal lengths");
  }
  if (!(trajectory.period > 0)) throw std::invalid_argument("the period must be positive");
  if (!(sample_time > 0) || !(duration > sample_time)) {
    throw std::invalid_argument("sample time and duration must be positive, duration longer");
  }
  const Eigen::Index n = static_cast<Eigen::Index>(std::ceil(duration / sample_time - 1e-9));
  const Eigen::Index dof = trajectory.q0.size();
  Trajectory out;
  out.t.resize(n);
  out.q.resize(n, dof);
  out.dq.resize(n, dof);
  out.ddq.resize(n, dof);
  out.tau = Eigen::MatrixXd::Zero(n, dof);
  out.has_velocity = true;
  Eigen::VectorXd q, dq, ddq;
  for (Eigen::Index s = 0; s < n; ++s) {
    out.t[s] = static_cast<double>(s) * sample_time;
    trajectory.evaluate(out.t[s], q, dq, ddq);
    out.q.row(s) = q;
    out.dq.row(s) = dq;
    out.ddq.row(s) = ddq;
  }
  return out;
}

}  // namespace modelgen
