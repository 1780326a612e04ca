// Equations near a reversal, left out before the decimation.

#include "modelgen/signal/reversal_mask.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace modelgen {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

Eigen::ArrayXXd reversal_mask(const Eigen::MatrixXd& dq, const Eigen::MatrixXd& K,
                              const Eigen::VectorXd& min_speed, Eigen::Index guard) {
  const Eigen::Index m = dq.rows(), n = dq.cols();
  Eigen::ArrayXXd mask = Eigen::ArrayXXd::Ones(m, n);
  if (min_speed.size() == 0) return mask;
  if (min_speed.size() != n || K.rows() != n || K.cols() != n || guard < 0) {
    throw std::invalid_argument("reversal_mask: " + std::to_string(min_speed.size()) +
                                " speeds and a " + std::to_string(K.rows()) + "x" +
                                std::to_string(K.cols()) + " drive chain for " + std::to_string(n) +
                                " joints, guard " + std::to_string(guard));
  }
  // Motor m's speed on its joint's scale; slow(s, k): joint k or motor k below its speed.
  const Eigen::MatrixXd motors = dq * K.transpose() * K.diagonal().cwiseInverse().asDiagonal();
  Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic> joint_slow(m, n), motor_slow(m, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    joint_slow.col(k) = dq.col(k).array().abs() < min_speed[k];
    motor_slow.col(k) = motors.col(k).array().abs() < min_speed[k];
  }
  for (Eigen::Index j = 0; j < n; ++j) {
    // Whether what enters equation j is slow at each sample.
    std::vector<char> slow(static_cast<std::size_t>(m), 0);
    for (Eigen::Index s = 0; s < m; ++s) {
      bool any = joint_slow(s, j) || motor_slow(s, j);
      for (Eigen::Index k = 0; k < n && !any; ++k) any = k != j && K(k, j) != 0 && motor_slow(s, k);
      slow[static_cast<std::size_t>(s)] = any;
    }
    // Distance to the nearest slow sample, both directions.
    std::vector<Eigen::Index> dist(static_cast<std::size_t>(m), m + 1);
    Eigen::Index last = -(m + 1);
    for (Eigen::Index s = 0; s < m; ++s) {
      if (slow[static_cast<std::size_t>(s)]) last = s;
      dist[static_cast<std::size_t>(s)] = s - last;
    }
    last = 2 * m + 2;
    for (Eigen::Index s = m - 1; s >= 0; --s) {
      if (slow[static_cast<std::size_t>(s)]) last = s;
      dist[static_cast<std::size_t>(s)] = std::min(dist[static_cast<std::size_t>(s)], last - s);
    }
    for (Eigen::Index s = 0; s < m; ++s) {
      const Eigen::Index d = dist[static_cast<std::size_t>(s)];
      if (d <= guard)
        mask(s, j) =
            0.5 - 0.5 * std::cos(kPi * static_cast<double>(d) / static_cast<double>(guard + 1));
    }
  }
  return mask;
}

Eigen::Index reversal_guard_samples(double cutoff_hz, double sample_rate_hz) {
  if (!(cutoff_hz > 0) || !(sample_rate_hz > 0)) return 0;
  return static_cast<Eigen::Index>(std::ceil(2.0 * sample_rate_hz / cutoff_hz));
}

}  // namespace modelgen
