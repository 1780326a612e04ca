// Peak a-priori torques of a Fourier excitation on the dense limit grid, its states evaluated
// by FFT blocks (fourier_grid.hpp).

#include "modelgen/excitation/torque_use.hpp"

#include <cmath>

#include "modelgen/excitation/limit_use.hpp"
#include "runtime/src/excitation/fourier_grid.hpp"

namespace modelgen {

std::vector<TorquePeak> torque_peaks(const IdentificationModel& model, const Eigen::VectorXd& beta,
                                     const FourierTrajectory& trajectory, double rate) {
  const long n = limit_grid_points(trajectory, rate);
  const int dof = model.dof();
  std::vector<detail::GridPeak> grid(static_cast<std::size_t>(dof));
  Eigen::VectorXd q(dof), dq(dof), ddq(dof), tau(dof);
  // The states by FFT blocks (fourier_grid.hpp); torques within 1e-10 of each other, relative,
  // are one peak, so the FFT's rounding does not choose between equal peaks.
  detail::for_each_grid_block(trajectory, n, [&](const detail::GridBlock& block) {
    for (Eigen::Index k = 0; k < block.q.rows(); ++k) {
      q = block.q.row(k).transpose();
      dq = block.dq.row(k).transpose();
      ddq = block.ddq.row(k).transpose();
      model.inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau.data());
      for (int j = 0; j < dof; ++j) {
        const double value = std::abs(tau[j]);
        grid[static_cast<std::size_t>(j)].offer(value, block.index(k), 1e-10 * value);
      }
    }
  });
  // The peaks at the chosen instants from the series itself, as a point-by-point evaluation of
  // the grid gives them.
  std::vector<TorquePeak> peaks(static_cast<std::size_t>(dof));
  for (int j = 0; j < dof; ++j) {
    const long s = grid[static_cast<std::size_t>(j)].index;
    if (s < 0) continue;
    TorquePeak& peak = peaks[static_cast<std::size_t>(j)];
    peak.time = trajectory.period * static_cast<double>(s) / static_cast<double>(n);
    trajectory.evaluate(peak.time, q, dq, ddq);
    model.inverse_dynamics(q.data(), dq.data(), ddq.data(), beta.data(), tau.data());
    peak.peak = std::abs(tau[j]);
  }
  return peaks;
}

}  // namespace modelgen
