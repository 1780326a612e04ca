// Shape and finiteness checks of trajectories, with messages naming sample, time and column.

#include "runtime/src/signal/trajectory_checks.hpp"

#include <cmath>
#include <cstdio>

namespace modelgen::detail {

std::string format(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

void fail(const Trajectory& x, const std::string& message) {
  throw DataError(SourceLocation{x.source},
                  (x.source.empty() ? "trajectory" : x.source) + ": error: " + message);
}

void check_shapes(const Trajectory& x, bool torque) {
  const Eigen::Index n = x.t.size(), dof = x.q.cols();
  auto check = [&](const Eigen::MatrixXd& m, const char* name) {
    if (m.rows() != n || m.cols() != dof) {
      fail(x, std::string(name) + " is " + std::to_string(m.rows()) + " x " +
                  std::to_string(m.cols()) + ", expected " + std::to_string(n) + " x " +
                  std::to_string(dof) + " (samples x axes)");
    }
  };
  check(x.q, "q");
  if (torque) check(x.tau, "tau");
  if (x.has_velocity) {
    check(x.dq, "dq");
    check(x.ddq, "ddq");
  }
}

void check_finite(const Trajectory& x, const Eigen::MatrixXd& m, const char* prefix) {
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index s = 0; s < m.rows(); ++s) {
      if (!std::isfinite(m(s, j))) {
        fail(x, "sample " + std::to_string(s + 1) + " (t = " + format(x.t[s]) + " s), column '" +
                    prefix + std::to_string(j + 1) + "' is NaN or infinite; data must be finite");
      }
    }
  }
}

}  // namespace modelgen::detail
