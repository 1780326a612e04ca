// The maximum-likelihood fit of fit.hpp (Swevers et al. 2002, eq. 18) restricted to physically
// possible values: the load's pseudo-inertia positive definite (Wensing, Kim & Slotine 2017)
// through its log-Cholesky parameters (Rucker & Wensing 2022, modelgen/model/pseudo_inertia.hpp),
// rotor inertias, viscous and Coulomb friction nonnegative and efficiencies in (0, 1] as
// bounds of Levenberg-Marquardt on Ceres. The link parameters other than the load are known in
// the ML problem, so the load and the drive parameters are all there is to constrain.
#pragma once

#include <string>
#include <vector>

#include "modelgen/ml/fit.hpp"
#include "modelgen/ml/problem.hpp"

namespace modelgen {

struct MlPhysicalOptions {
  /// Weight of the prior term towards the start (the unconstrained estimate made consistent):
  /// the sum of squared relative deviations of the load's standard parameters and of the drive
  /// unknowns, against eq. 18's weighted sum of squares. Small: it only settles directions the
  /// data leave free, as in modelgen/estimation/physical.hpp.
  double prior_weight = 1e-6;
  int max_iterations = 200;  ///< Levenberg-Marquardt iterations
  int threads = 2;           ///< Ceres evaluation threads
};

struct MlPhysicalResult {
  /// The consistent estimate, reported as fit_ml reports one; std_dev is NaN where the
  /// unconstrained fit found the unknown not identifiable. An unknown held at its bound gets
  /// the marginal standard deviation with it free, at the consistent optimum (the unconstrained
  /// covariance's part in the held direction, as the least-squares fit reports: an upper bound;
  /// the local covariance of the active set would give it 0).
  MlFitResult fit;
  /// Per unknown of fit.names: held on its bound by the consistent fit.
  std::vector<bool> at_bound;
  /// The load's pseudo-inertia ended on the boundary of the consistent set.
  bool load_on_boundary = false;
  /// Eq. 18's weighted sum of squares (noise variances as units) of the unconstrained
  /// estimate, and the increase the consistent one adds to it (0 when the unconstrained one
  /// was consistent already).
  double unconstrained_sum_of_squares = 0;
  double cost_increase = 0;
  /// The constraints the estimate sits on, in words ("Rv3 >= 0", "load pseudo-inertia > 0").
  std::vector<std::string> binding;
  /// The unconstrained estimate was consistent; `fit` is that estimate.
  bool unconstrained_consistent = false;
};

/// What makes the unknowns of `fit` physically impossible, one entry per violated condition
/// ("Rv3 = -2.1 < 0", "load: ..."); empty when nothing is. Unknowns the data do not identify
/// (NaN) are judged at the value the fit held them at.
std::vector<std::string> ml_physical_violations(const MlProblem& problem, const MlFitResult& fit);

/// The consistent fit of `problem`, started from `unconstrained` (fit_ml's result on the same
/// problem) made consistent: the load's pseudo-inertia with its eigenvalues floored, the drive
/// parameters clipped to their bounds. Returns `unconstrained` itself when it is consistent.
/// Throws EstimationError when `unconstrained` has other unknowns than `problem`, when only
/// some of the load's ten parameters are unknown (a known mass
/// with an unknown centre of gravity, say: the log-Cholesky parameters couple all ten) or the
/// search fails numerically.
MlPhysicalResult fit_ml_physical(MlProblem& problem, const MlFitResult& unconstrained,
                                 const MlPhysicalOptions& options = {});

}  // namespace modelgen
