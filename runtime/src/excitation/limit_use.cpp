// Extremes of a Fourier excitation on a dense grid, and their use of the joint limits.

#include "modelgen/excitation/limit_use.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace modelgen {

long limit_grid_points(const FourierTrajectory& trajectory, double rate) {
  const double by_rate = std::ceil(trajectory.period * rate);
  const double by_harmonic = 1000.0 * static_cast<double>(std::max<Eigen::Index>(trajectory.a.cols(), 1));
  return static_cast<long>(std::max(by_rate, by_harmonic));
}

std::vector<JointExtremes> trajectory_extremes(const FourierTrajectory& trajectory, double rate) {
  const long n = limit_grid_points(trajectory, rate);
  const Eigen::Index dof = trajectory.q0.size();
  std::vector<JointExtremes> extremes(static_cast<std::size_t>(dof));
  Eigen::VectorXd q, dq, ddq;
  for (long s = 0; s < n; ++s) {
    const double t = trajectory.period * static_cast<double>(s) / static_cast<double>(n);
    trajectory.evaluate(t, q, dq, ddq);
    for (Eigen::Index j = 0; j < dof; ++j) {
      JointExtremes& e = extremes[static_cast<std::size_t>(j)];
      if (s == 0 || q[j] < e.q_min) e.q_min = q[j], e.q_min_time = t;
      if (s == 0 || q[j] > e.q_max) e.q_max = q[j], e.q_max_time = t;
      if (s == 0 || std::abs(dq[j]) > e.dq_peak) e.dq_peak = std::abs(dq[j]), e.dq_time = t;
      if (s == 0 || std::abs(ddq[j]) > e.ddq_peak) e.ddq_peak = std::abs(ddq[j]), e.ddq_time = t;
    }
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
    if (!limits[j].q_lower || !limits[j].q_upper) missing.emplace_back(joint, "q");
    if (!limits[j].dq) missing.emplace_back(joint, "dq");
    if (!limits[j].ddq) missing.emplace_back(joint, "ddq");
  }
  return missing;
}

}  // namespace modelgen
