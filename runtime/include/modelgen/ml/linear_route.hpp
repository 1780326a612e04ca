// The linear route of Swevers et al. 2002: the initial guess of section 3.2 and approach 1 of
// section 4. With the transmission efficiencies fixed to 1 the drive model (eq. 12) is linear in
// the inertial parameters of the links, the rotor inertias and the motor friction. The
// combinations of them that the experiment identifies (the base, or barycentric, parameters of
// the moving part of the robot with its load) are estimated by weighted least squares (the
// Markov estimate of Swevers et al. 1997), and the load, friction and rotor inertias are then
// solved from those estimates and the a-priori values of the links.
#pragma once

#include <Eigen/Core>
#include <string>

#include "modelgen/ml/fit.hpp"
#include "modelgen/ml/problem.hpp"

namespace modelgen {

struct LinearRoute {
  /// problem.values() with the unknowns from the route, the starting point of the nonlinear
  /// search: unknown efficiencies 1, the other unknowns solved from the base-parameter
  /// estimates. Values the route cannot determine stay as given (minimum-norm solution on
  /// column-scaled unknowns), and so does the whole load when its estimated mass is not positive.
  Eigen::VectorXd values;
  /// Approach 1 as a result of the fit (iterations 0): the unknowns are problem's unknowns
  /// without the efficiencies (fixed to 1), then the rotor inertias JMj of the fitted motors
  /// (unknown in approach 1). identifiability is that of the equations that give these from the
  /// base parameters, in load terms; std_dev propagates the base parameters' covariance through
  /// them; rms_error and residual_std_dev are those of the linear model, whose many parameters fit
  /// the torques better than the physical model with the same load would (section 4,
  /// discussion of Table 3).
  MlFitResult fit;
  int excited_parameters = 0;  ///< parameters of the linear model the data move at all
  int base_parameters = 0;     ///< identifiable combinations of them: rank of the regressor
};

/// Runs the route on `problem` (its values() are the a-priori values and the given starting
/// point). `rank_tolerance` decides the rank of the equations for the load (as identifiability()).
/// Never throws for data that MlProblem accepted; what could not be done is said in fit.notes.
LinearRoute linear_route(const MlProblem& problem, double rank_tolerance = 1e-9);

}  // namespace modelgen
