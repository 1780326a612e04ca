// The Coulomb friction of a model's base parameters, taken apart so that a simulation can
// smooth it: sign(v) jumps at rest, and an explicit integrator stepping across the jump makes
// a torque that no friction has (chatter around zero velocity). Private to closed_loop/.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/model/identification_model.hpp"

namespace modelgen::detail {

/// One Coulomb term of the inverse dynamics: torque = value * a * phi(c . dq), phi the sign
/// (Fc, Fcm), the step at positive velocity (Fcp) or minus the step at negative velocity (Fcn).
struct CoulombTerm {
  enum class Shape { kSign, kPositive, kNegative };
  int param = 0;        ///< index in the base parameters
  Shape shape = Shape::kSign;
  Eigen::VectorXd c;    ///< velocity the friction acts on: v = c . dq
  Eigen::VectorXd a;    ///< joint torques per unit of friction
  double value = 0;     ///< the base parameter
  double smoothing = 0; ///< velocity scale of the smooth step, rad/s (m/s)
};

/// The Coulomb terms of `model` for base parameters `beta`, by name: Fc<j>, Fcp<j>, Fcn<j>
/// (joint j) and Fcm<j> (motor j, velocity row j of the drive chain's K divided by K_jj, as the
/// description's coupled-motor friction). Checks the decomposition against the model's own
/// inverse dynamics at random velocities and throws std::logic_error naming the model if it
/// does not reproduce it (a base parameter that regroups Coulomb friction with something else).
std::vector<CoulombTerm> coulomb_terms(const IdentificationModel& model,
                                       const std::vector<double>& beta);

/// The torques of the terms with phi smoothed: sign -> tanh(v / eps), the steps ->
/// (1 +- tanh(v / eps)) / 2, eps = the term's smoothing.
void smoothed_coulomb_torque(const std::vector<CoulombTerm>& terms, const double* dq,
                             Eigen::VectorXd& tau);

}  // namespace modelgen::detail
