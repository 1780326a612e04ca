// Peak a-priori torques of a Fourier excitation on the dense limit grid.

#include "modelgen/excitation/torque_use.hpp"

#include <cmath>

#include "modelgen/excitation/limit_use.hpp"

namespace modelgen {

std::vector<TorquePeak> torque_peaks(const IdentificationModel& model, const Eigen::VectorXd& beta,
                                     const FourierTrajectory& trajectory, double rate) {
  const long n = limit_grid_points(trajectory, rate);
  std::vector<TorquePeak> peaks(static_cast<std::size_t>(model.dof()));
  Eigen::VectorXd q, dq, ddq, tau(model.dof());
  for (long s = 0; s < n; ++s) {
    const double t = trajectory.period * static_cast<double>(s) / static_cast<double>(n);
    trajectory.evaluate(t, q, dq, ddq);
    model.inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau.data());
    for (int j = 0; j < model.dof(); ++j) {
      TorquePeak& peak = peaks[static_cast<std::size_t>(j)];
      if (std::abs(tau[j]) > peak.peak) peak.peak = std::abs(tau[j]), peak.time = t;
    }
  }
  return peaks;
}

}  // namespace modelgen
