// Swevers et al. 2002, eq. 4: motor torque from current by a sign-symmetric cubic polynomial
// in |I|, times the transmission ratio.

#include "modelgen/data/motor_current.hpp"

#include <cmath>

#include "modelgen/data/data_error.hpp"

namespace modelgen {

double motor_torque_from_current(double current, const CurrentTorquePolynomial& motor) {
  if (current == 0) return 0;
  const double a = std::abs(current);
  const double magnitude = motor.c[0] + a * (motor.c[1] + a * (motor.c[2] + a * motor.c[3]));
  return motor.ratio * (current > 0 ? magnitude : -magnitude);
}

Eigen::MatrixXd motor_torques_from_currents(const Eigen::MatrixXd& currents,
                                            const std::vector<CurrentTorquePolynomial>& motors,
                                            const std::string& source) {
  if (static_cast<Eigen::Index>(motors.size()) != currents.cols()) {
    throw DataError(source + ": error: " + std::to_string(currents.cols()) +
                    " current columns but " + std::to_string(motors.size()) +
                    " current-torque polynomials; give one per motor");
  }
  Eigen::MatrixXd torque(currents.rows(), currents.cols());
  for (Eigen::Index j = 0; j < currents.cols(); ++j) {
    for (Eigen::Index s = 0; s < currents.rows(); ++s) {
      const double current = currents(s, j);
      if (!std::isfinite(current)) {
        throw DataError(SourceLocation{source, 0, 0, "i" + std::to_string(j + 1)},
                        source + ": sample " + std::to_string(s) + " (column i" +
                            std::to_string(j + 1) + "): error: current is NaN or infinite");
      }
      torque(s, j) = motor_torque_from_current(current, motors[j]);
    }
  }
  return torque;
}

}  // namespace modelgen
