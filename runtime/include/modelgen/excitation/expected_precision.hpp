// What an excitation promises before any data: the standard deviations a least-squares fit
// of its stacked regressor would have for a given torque noise (Gautier & Briot eq. 18 with
// the noise known instead of estimated from the residual). modelid design reports them as
// the expected %std of every base parameter.
#pragma once

#include <Eigen/Core>

namespace modelgen {

/// sqrt of the diagonal of noise^2 (W^T W)^-1: the standard deviation of each parameter of an
/// OLS fit y = W beta + e with independent errors e of standard deviation `noise` on every
/// equation. `W` is equations x parameters. Computed from a QR factor of W (never W^T W, whose
/// condition is the square of W's). Throws std::invalid_argument for a W with fewer rows than
/// columns, of deficient column rank, or for a noise that is not positive.
Eigen::VectorXd expected_std_devs(const Eigen::MatrixXd& W, double noise);

}  // namespace modelgen
