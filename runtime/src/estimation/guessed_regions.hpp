// Regions guessed from the joints' positions (no shapes, no `region:` given) are assumptions,
// not facts about the robot: a capsule a quarter as thick as the segments between the joints
// misses a counterweight behind the elbow or a link offset from its axes. The fit therefore
// tests them against the data: enforced, they must not raise the weighted sum of squares beyond
// what chance allows for the constraints they add, else the data reject them and the fit runs
// without them.

#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "modelgen/estimation/physical.hpp"

namespace modelgen::detail {

// The fit of modelgen/estimation/physical.hpp with exactly options.regions enforced (those of
// bodies without a-priori inertials), no test of the guesses (physical.cpp).
PhysicalFitResult fit_physical_within(const RigidBodyTree& tree, const Eigen::MatrixXd& K,
                                      const Eigen::VectorXd& beta_hat,
                                      const Eigen::MatrixXd& information,
                                      const std::vector<std::optional<double>>& prior,
                                      const PhysicalFitOptions& options);

// The 99.9 % point of the chi-square distribution with `dof` degrees of freedom
// (Wilson-Hilferty): the largest rise of the weighted sum of squares, in sigma^2, that `dof`
// constraints true of the robot leave by chance.
double chi_square_999(int dof);

}  // namespace modelgen::detail
