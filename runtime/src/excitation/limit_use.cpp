// Extremes of a Fourier excitation on a dense grid, and their use of the joint limits. The grid
// is evaluated by FFT blocks (fourier_grid.hpp), so its cost does not multiply with the harmonics.

#include "modelgen/excitation/limit_use.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "runtime/src/excitation/fourier_grid.hpp"

namespace modelgen {

// The grid rule (limit_use.hpp): the spacing of n >= 1000 L points per period puts every
// instant within pi / (1000 L wf) of a grid point, and a series of L harmonics has
// |f''| <= (L wf)^2 max|f - mean| (Bernstein's inequality), so at a peak, where f' = 0, the grid
// misses at most (pi / 1000)^2 / 2 = 4.9e-6 of the oscillation's amplitude.
long limit_grid_points(const FourierTrajectory& trajectory, double rate) {
  const long harmonics = std::max<long>(static_cast<long>(trajectory.a.cols()), 1);
  const double by_rate = std::ceil(trajectory.period * rate);
  const double by_harmonic = 1000.0 * static_cast<double>(harmonics);
  long n = static_cast<long>(std::max(by_rate, by_harmonic));
  // The grid is evaluated by FFT blocks of detail::grid_block(n) points; blocks much shorter
  // than L would make the cost grow with L again (fourier_grid.hpp), so such an n is rounded up
  // to a multiple of the power of two >= L: fewer than 2 L points more, under 0.2%.
  if (8 * detail::grid_block(n) < harmonics) {
    long block = 1;
    while (block < harmonics) block *= 2;
    n = (n + block - 1) / block * block;
  }
  return n;
}

std::vector<JointExtremes> trajectory_extremes(const FourierTrajectory& trajectory, double rate) {
  const long n = limit_grid_points(trajectory, rate);
  const Eigen::Index dof = trajectory.q0.size();
  // Per joint: the largest q, -q, |dq| and |ddq| on the grid; values within 1e-10 of the
  // series' bound of each other (the FFT rounds to about 1e-15 of it) count as one peak.
  std::vector<std::array<detail::GridPeak, 4>> peaks(static_cast<std::size_t>(dof));
  const detail::SeriesBounds bounds = detail::series_bounds(trajectory);
  const Eigen::VectorXd q_scale = 1e-10 * (bounds.q + trajectory.q0.cwiseAbs());
  const Eigen::VectorXd dq_scale = 1e-10 * bounds.dq, ddq_scale = 1e-10 * bounds.ddq;
  detail::for_each_grid_block(trajectory, n, [&](const detail::GridBlock& block) {
    for (Eigen::Index k = 0; k < block.q.rows(); ++k) {
      const long s = block.index(k);
      for (Eigen::Index j = 0; j < dof; ++j) {
        auto& p = peaks[static_cast<std::size_t>(j)];
        p[0].offer(block.q(k, j), s, q_scale[j]);
        p[1].offer(-block.q(k, j), s, q_scale[j]);
        p[2].offer(std::abs(block.dq(k, j)), s, dq_scale[j]);
        p[3].offer(std::abs(block.ddq(k, j)), s, ddq_scale[j]);
      }
    }
  });
  // The values at the chosen instants from the series itself, as a point-by-point evaluation
  // of the grid gives them.
  std::vector<JointExtremes> extremes(static_cast<std::size_t>(dof));
  Eigen::VectorXd q, dq, ddq;
  for (Eigen::Index j = 0; j < dof; ++j) {
    const auto& p = peaks[static_cast<std::size_t>(j)];
    JointExtremes& e = extremes[static_cast<std::size_t>(j)];
    const auto time = [&](int key) {
      return trajectory.period * static_cast<double>(p[key].index) / static_cast<double>(n);
    };
    e.q_max_time = time(0);
    trajectory.evaluate(e.q_max_time, q, dq, ddq);
    e.q_max = q[j];
    e.q_min_time = time(1);
    trajectory.evaluate(e.q_min_time, q, dq, ddq);
    e.q_min = q[j];
    e.dq_time = time(2);
    trajectory.evaluate(e.dq_time, q, dq, ddq);
    e.dq_peak = std::abs(dq[j]);
    e.ddq_time = time(3);
    trajectory.evaluate(e.ddq_time, q, dq, ddq);
    e.ddq_peak = std::abs(ddq[j]);
  }
  return extremes;
}

std::vector<LimitUse> limit_uses(const std::vector<JointExtremes>& extremes,
                                 const std::vector<JointLimits>& limits) {
  std::vector<LimitUse> uses;
  for (std::size_t j = 0; j < extremes.size() && j < limits.size(); ++j) {
    const JointExtremes& e = extremes[j];
    const JointLimits& limit = limits[j];
    const int joint = static_cast<int>(j);
    if (limit.q_lower && limit.q_upper) {
      const double middle = (*limit.q_lower + *limit.q_upper) / 2;
      const double half = (*limit.q_upper - *limit.q_lower) / 2;
      const double up = (e.q_max - middle) / half, down = (middle - e.q_min) / half;
      uses.push_back(up >= down ? LimitUse{joint, "q", e.q_max, *limit.q_upper, e.q_max_time, up}
                                : LimitUse{joint, "q", e.q_min, *limit.q_lower, e.q_min_time, down});
    }
    if (limit.dq) uses.push_back({joint, "dq", e.dq_peak, *limit.dq, e.dq_time, e.dq_peak / *limit.dq});
    if (limit.ddq) {
      uses.push_back({joint, "ddq", e.ddq_peak, *limit.ddq, e.ddq_time, e.ddq_peak / *limit.ddq});
    }
  }
  return uses;
}

std::vector<std::pair<int, std::string>> missing_limits(const std::vector<JointLimits>& limits) {
  std::vector<std::pair<int, std::string>> missing;
  for (std::size_t j = 0; j < limits.size(); ++j) {
    const int joint = static_cast<int>(j);
    const bool has_q = (limits[j].q_lower && limits[j].q_upper) || limits[j].continuous;
    if (!has_q) missing.emplace_back(joint, "q");
    if (!limits[j].dq) missing.emplace_back(joint, "dq");
    if (!limits[j].ddq) missing.emplace_back(joint, "ddq");
  }
  return missing;
}

}  // namespace modelgen
