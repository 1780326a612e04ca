// Motor torque from measured motor current for permanent-magnet synchronous motors: the
// third-order sign-symmetric polynomial of Swevers et al. 2002, eq. 4, scaled to the link side by
// the transmission ratio.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace modelgen {

/// One motor's current-torque relation (Swevers eq. 4):
/// tau_M = ratio * sign(I) * (c0 + c1 |I| + c2 I^2 + c3 |I|^3), with sign(0) = 0.
struct CurrentTorquePolynomial {
  double ratio = 1;  ///< mu, transmission ratio (link-side torque per motor torque)
  std::array<double, 4> c{0, 0, 0, 0};  ///< c0 (N m), c1 (N m/A), c2 (N m/A^2), c3 (N m/A^3)
};

/// The motor torque (link side, N m) for a current in A. Zero current gives zero torque.
double motor_torque_from_current(double current, const CurrentTorquePolynomial& motor);

/// Applies motor_torque_from_current to every sample: `currents` is samples x motors (A), one
/// polynomial per motor; returns samples x motors torques (N m, link side).
/// Throws DataError (modelgen/data/data_error.hpp) naming `source`, the sample (0-based row)
/// and the column (i1..in) for a non-finite current, and for a number of polynomials that is not
/// the number of columns.
Eigen::MatrixXd motor_torques_from_currents(const Eigen::MatrixXd& currents,
                                            const std::vector<CurrentTorquePolynomial>& motors,
                                            const std::string& source);

}  // namespace modelgen
