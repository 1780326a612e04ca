// The initial guess of the maximum-likelihood fit by the linear route of Swevers et al. 2002,
// section 3.2, in a simple form: with the transmission efficiencies fixed to 1 the drive model
// is linear in the inertial parameters, JM, Rv and Rc, so one weighted least-squares solve on
// the payload link's standard parameters and the unknown drive parameters (the known link
// parameters subtracted through the model) gives their estimate, and the load follows from the
// payload's standard parameters (load_from_standard).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "modelgen/ml_problem.hpp"

namespace modelgen {

/// Returns problem.values() with the unknowns replaced by the linear estimate: unknown Rz set to
/// 1, the other unknown drive and inertial parameters from the weighted least-squares solution
/// of eq. 18 linearised there (exact when every Rz is 1), the load from the payload's estimated
/// standard parameters minus the link's own values. Parameters the linear model cannot
/// determine move least from their given values (minimum-norm step on column-scaled unknowns).
/// What could not be done (a load whose estimated mass is not positive keeps its given values)
/// is appended to `notes` in words.
Eigen::VectorXd linear_initial_guess(const MlProblem& problem, std::vector<std::string>& notes);

}  // namespace modelgen
