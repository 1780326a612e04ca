// The prior term of the physically consistent fit (physical.cpp): its centre (the a-priori
// standard values, or the start where there are none); for each body with a-priori inertials
// the log-det divergence of pseudo-inertias; for every other parameter a quadratic pull,
// relative to a scale, confined to the directions the data do not determine (the null space
// of the regrouping map K); and the rule that chooses its default weight.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/estimation/physical.hpp"
#include "modelgen/model/rigid_body_tree.hpp"
#include "runtime/src/estimation/physical_barrier.hpp"

namespace modelgen::detail {

// The default weight rule of --physical (docs/methods.md, "The a-priori model as the prior"):
// the largest weight of kPriorWeightLadder whose estimate raises the fit's weighted sum of
// squares by at most kCostRiseLimit of the unconstrained fit's beyond what consistency alone
// costs (the estimate with kReferencePriorWeight): in sigma^2 units, with F the unconstrained
// fit's information matrix and S0 its weighted sum of squares (the residual degrees of freedom),
// ||beta_w - beta_hat||_F^2 - ||beta_ref - beta_hat||_F^2 <= kCostRiseLimit S0: the rms of the
// weighted residual grows by at most 2 % (1.02^2 = 1 + 0.0404) for the prior. Relative, not in
// standard deviations, because F grows with the record's length while the part of the residual
// that model error makes does not shrink: on the real Panda run (1231 residual degrees of
// freedom, consistency alone +9 % of S0) a tenth of a standard deviation left only weight 1e-6,
// and links at 12 times their a-priori mass; weight 1 costs 3.4 % of S0 there. Where S0 is not
// given the rise may be 1 sigma^2 (no base parameter moves by more than its standard deviation,
// |d beta_j| <= sigma_j ||d beta||_F), the statistical bound when the residual is noise alone.
// The reference weight is the smallest that keeps the problem well posed.
inline constexpr double kPriorWeightLadder[] = {1.0, 1e-1, 1e-2, 1e-3, 1e-4};
inline constexpr double kReferencePriorWeight = modelgen::kReferencePriorWeight;
inline constexpr double kCostRiseLimit = 1.02 * 1.02 - 1;
inline constexpr double kCostRiseWithoutResidual = 1.0;

// Scales for the prior term: the largest reference value of the parameter's group (a body's
// inertia entries, its first moments, its mass; all drive parameters of one kind), so that a
// deviation counts relative to the size of what it belongs to, zero-valued products of inertia
// included; floored at 1e-3 of the largest group of its class (inertias, first moments,
// masses). Given `base_std_dev` (the prior on every direction, without a-priori values), also
// floored at what the data resolve of the parameter (the smallest sigma_j / |K_jk| over the
// base parameters j it enters), so that a parameter the data leave at nearly zero does not get
// an enormous weight.
Eigen::VectorXd prior_scales(const RigidBodyTree& tree, const Layout& layout,
                             const Eigen::VectorXd& reference, const Eigen::MatrixXd& K,
                             const Eigen::VectorXd* base_std_dev);

// The prior of a body whose ten a-priori values form a positive definite pseudo-inertia P0:
// the log-det (Bregman) divergence of pseudo-inertias (Lee & Park, RA-L 2018; Lee, Wensing &
// Park, T-RO 2020, "Geometric robot dynamic identification"),
//     D(P || P0) = -log det(P0^-1 P) + tr(P0^-1 P) - 4,
// the Bregman divergence of -log det: 0 at P = P0 only, the same in every frame and unit
// (P -> S P S' leaves it unchanged), infinite on the boundary of consistency, so that a body
// it holds stays strictly inside; 1/2 tr(P0^-1 dP P0^-1 dP) to second order (the local form
// this replaced, which let principal moments fall to 1e-7 on the real Panda run). Over a body's
// ten variables x (physical_barrier.hpp, P = sum_e x_e E_e): gradient tr((P0^-1 - P^-1) E_e),
// Hessian tr(P^-1 E_e P^-1 E_f). nullopt where P is not positive definite.
struct BodyDivergence {
  double value = 0;
  Eigen::Matrix<double, 10, 1> gradient = Eigen::Matrix<double, 10, 1>::Zero();
  Eigen::Matrix<double, 10, 10> hessian = Eigen::Matrix<double, 10, 10>::Zero();
};
std::optional<BodyDivergence> log_det_divergence(const Eigen::Matrix4d& P0, const double* x,
                                                 bool derivatives = true);

// The centre of a body's divergence prior: its a-priori pseudo-inertia P0, or, where that is
// singular or nearly so (a point mass, a rod, a plate: idealisations, not bodies; the
// divergence needs P0 positive definite), P0 with the same mass and first moments and the mass
// spread along each thin principal axis to the rms extent of a uniform solid sphere of radius
// `radius` about the centre of mass (second moment m r^2 / 5 per axis). An axis is thin when
// its second moment about the centre of mass is below kThinAxisFraction of the sphere's (rms
// extent below a tenth of r / sqrt 5: about 1 mm for r = 2.5 cm): thinner than any part that
// is made, so the spread changes no body a vendor could have measured or modelled in CAD.
inline constexpr double kThinAxisFraction = 1e-2;
struct DivergenceCentre {
  Eigen::Matrix4d P0;
  int thin_axes = 0;  // spread: 3 a point mass, 2 mass on a line, 1 mass in a plane; 0 as given
  double radius = 0;  // of the sphere whose spread the thin axes were given
};
// nullopt where the a-priori values are no body (mass not positive, P0 not positive
// semidefinite to 1e-12 of its largest eigenvalue): the quadratic prior keeps them.
std::optional<DivergenceCentre> divergence_centre(const double* p0, double radius);

// The sphere's radius for a body's spread (above): half the smallest semi-axis of its region
// (the body's geometry, or the guess from its joints) where it has one, so that the sphere lies
// well inside it; else a twentieth of the robot's scale, the summed lengths of the bodies'
// fixed translations (its reach along the chain; TX-40: 0.45 m, r = 2.3 cm, about the
// flange's radius).
double spread_radius(const RigidBodyTree& tree, const std::optional<BodyRegion>& region);

// The output's note on a body spread by divergence_centre (thin_axes > 0).
std::string spread_note(const std::string& body_name, const DivergenceCentre& centre);

// Per layout body, the centre (divergence_centre, radius per layout body) of a body all ten of
// whose values are given; nullopt for the others, which the quadratic prior keeps.
std::vector<std::optional<DivergenceCentre>> divergence_centres(
    const Layout& layout, const Eigen::VectorXd& prior_value, const std::vector<char>& has_a_priori,
    const std::vector<double>& radius);

// w sum_b D(P_b(y) || centre_b) over the bodies with a centre (in the variables' units), as the
// barrier's convex term.
ConvexTerm divergence_term(const Layout& layout,
                           const std::vector<std::optional<Eigen::Matrix4d>>& centre,
                           double weight);

// The quadratic part of the prior, per unit weight: ||G1 y - g1||^2 = ||N' L_Q (p_Q - p0_Q)||^2
// over the parameters Q outside the divergence's bodies (drive parameters, bodies without
// complete a-priori values), L_Q = diag(1 / scale), N an orthonormal basis of the null space
// of K_Q L_Q^-1 (K's columns of Q): a pull in the directions of Q that change no base
// parameter. `standard_per_y` maps the variables to the standard parameters (T diag(1/d)).
struct QuadraticPrior {
  Eigen::MatrixXd G1;
  Eigen::VectorXd g1;
};
QuadraticPrior quadratic_prior(const Eigen::MatrixXd& K, const Eigen::MatrixXd& standard_per_y,
                               const Eigen::VectorXd& scale, const Eigen::VectorXd& prior_value,
                               const std::vector<char>& in_divergence);

// An orthonormal basis (columns) of the null space of K M: the directions (in the coordinates
// of M's inverse) that change no base parameter. The rank is decided relative to the largest
// singular value (1e-10), as the regrouping of rounding-level coefficients would otherwise
// count as information.
Eigen::MatrixXd null_space_of(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M);

// null_space_of(K, diag(scale)).
Eigen::MatrixXd scaled_null_space(const Eigen::MatrixXd& K, const Eigen::VectorXd& scale);

}  // namespace modelgen::detail
