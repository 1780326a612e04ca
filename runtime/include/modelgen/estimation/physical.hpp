// Physically consistent identification: the base parameters nearest (in the metric of the
// unconstrained fit's information matrix) to an unconstrained estimate that some physically
// consistent standard parameters produce, and those standard parameters.
//
// Each body's pseudo-inertia (Wensing, Kim & Slotine 2017; modelgen/model/pseudo_inertia.hpp) is
// kept positive definite and rotor inertias and friction coefficients nonnegative: a convex
// problem, solved to its global optimum by a barrier method; the standard deviations come from
// the log-Cholesky parametrisation (Rucker & Wensing 2022) at the optimum. For a linear
// least-squares fit the cost is exact: with beta_hat the unconstrained estimate and F = W'W /
// sigma^2 its information matrix, ||W beta - y||^2 / sigma^2 = ||W beta_hat - y||^2 / sigma^2 +
// (beta - beta_hat)' F (beta - beta_hat). A prior term towards the a-priori standard values
// (the description's inertials) picks one among the standard parameter sets that give the same
// base parameters: per link with a-priori inertials the log-det divergence of pseudo-inertias
// (Lee, Wensing & Park, T-RO 2020), which keeps the link strictly inside the consistent set;
// elsewhere a quadratic pull in the directions the data do not determine; with a weight chosen
// so that it raises the fit's weighted sum of squares by at most 4 % of the unconstrained fit's
// beyond what consistency costs (runtime/src/estimation/physical_prior.hpp, docs/methods.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/model/rigid_body_tree.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen {

class IdentificationModel;

/// The smallest prior weight that keeps the consistent solve well posed: its estimate is
/// "consistency alone", the default rule's reference. Below it the barrier's steps run into the
/// rounding of the data term and the solve may stop short (PhysicalFitResult::converged).
inline constexpr double kReferencePriorWeight = 1e-6;

struct PhysicalFitOptions {
  /// Weight of the prior term, against the base-parameter term in units of the estimate's
  /// variance: per link with ten a-priori values the log-det divergence of its pseudo-inertia
  /// from theirs; on every other parameter the sum of squares of the scaled deviation from the
  /// a-priori values (or, without one, from the start), each deviation relative to the size of
  /// the parameter's group (a body's inertia entries, first moments, mass; one drive kind),
  /// projected onto the directions that change no base parameter. Must be > 0. Unset: the default
  /// rule, the largest of 1, 0.1, ..., 1e-4 whose cost exceeds that of the estimate with weight
  /// 1e-6 (consistency alone) by at most 0.0404 residual_sum_of_squares (the weighted residual's
  /// rms grows by at most 2 % of the unconstrained fit's), else 1e-6. Without a body whose ten
  /// a-priori values are all given, the prior acts on every direction instead, relative to group
  /// sizes floored at what the data resolve, with weight 1e-6.
  std::optional<double> prior_weight;
  /// The unconstrained fit's weighted sum of squares in the information's units (for least
  /// squares with F = W'W / sigma^2: the residual degrees of freedom, rows - b), the scale of
  /// the default weight rule. Must be > 0. Unset: the rule allows a rise of 1 sigma^2.
  std::optional<double> residual_sum_of_squares;
  int max_iterations = 2000;  ///< Newton steps of the barrier method
  /// Per tree.bodies entry, the region its mass must stay in (RobotModel::body_regions; may be
  /// shorter or empty): tr(P Q) >= 0 of Wensing, Kim & Slotine (RA-L 2017), the body's rms
  /// extent in the ellipsoid at most 1, kept by a log barrier like the pseudo-inertia's.
  std::vector<std::optional<BodyRegion>> regions;
};

struct PhysicalFitResult {
  Eigen::VectorXd standard;      ///< consistent standard parameters, tree.params order
  Eigen::VectorXd base;          ///< K standard: the constrained base estimate
  /// From the Jacobian at the optimum in the free directions; in the directions binding
  /// constraints hold, the unconstrained spread (an upper bound: never 0 on the boundary).
  Eigen::VectorXd base_std_dev;
  /// (base - beta_hat)' F (base - beta_hat): what the constraints cost, in the unconstrained
  /// fit's variance units (for least squares: the increase of the weighted sum of squares
  /// divided by sigma^2; 0 when the unconstrained estimate is already consistent).
  double cost_increase = 0;
  /// The constraints that hold with equality at the optimum, in words, e.g. "Fv3 >= 0" or
  /// "body 'link4': mass distribution at the boundary (pseudo-inertia nearly singular)".
  std::vector<std::string> active_constraints;
  /// The tree.bodies indices of the bodies whose region holds at the optimum (its constraint
  /// pushes: the mass reaches the ellipsoid's rms edge), against the data or the prior.
  std::vector<int> region_bound_bodies;
  /// The bodies whose guessed regions (BodyRegion::guessed) were dropped: those holding the
  /// fit raised the weighted sum of squares by rejected_region_cost (sigma^2), beyond chance
  /// for so many constraints, so the result is the fit without any guess.
  std::vector<int> rejected_region_bodies;
  double rejected_region_cost = 0;
  /// The prior term's centre and scale per standard parameter: the a-priori value (or the
  /// start) and the size its deviation is measured against by the quadratic prior (links with
  /// a-priori inertials: the divergence, physical_prior.hpp).
  Eigen::VectorXd prior, prior_scale;
  /// In words, the bodies whose a-priori inertia is singular (a point mass, a rod, a plate),
  /// whose divergence prior uses it spread over a small sphere (physical_prior.hpp).
  std::vector<std::string> prior_notes;
  double prior_weight = 0;              ///< the weight used
  bool prior_weight_automatic = false;  ///< chosen by the default rule
  bool converged = false;
  int iterations = 0;  ///< Newton steps
};

/// The regrouping matrix K (beta = K p) of an identification model, column by column from
/// base_from_standard.
Eigen::MatrixXd regrouping_matrix(const IdentificationModel& model);

/// The physically consistent fit (header comment). `K` is num_base x tree.params.size();
/// `beta_hat` the unconstrained estimate; `information` its inverse covariance (symmetric
/// positive definite, num_base square); `prior` per standard parameter an a-priori value or
/// nullopt. The start: the standard parameters nearest the a-priori values that reproduce
/// beta_hat (it also serves as the prior where there is none), projected onto the consistent
/// set. Deterministic. Throws EstimationError on mismatched sizes, a non-finite input, a prior
/// weight that is not positive, or an information matrix that is not positive definite.
PhysicalFitResult fit_physical(const RigidBodyTree& tree, const Eigen::MatrixXd& K,
                               const Eigen::VectorXd& beta_hat, const Eigen::MatrixXd& information,
                               const std::vector<std::optional<double>>& prior,
                               const PhysicalFitOptions& options = {});

}  // namespace modelgen
