// The prior term of the physically consistent fit (physical.cpp): its centre (the a-priori
// standard values, or the start where there are none), the scale each deviation is measured
// against, and the projection that confines it to the directions the data do not determine
// (the null space of the regrouping map K), with the rule that chooses its default weight.
#pragma once

#include <vector>

#include <Eigen/Core>

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
inline constexpr double kReferencePriorWeight = 1e-6;
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

// The metric of the prior term, as a root L (n x n, block diagonal, invertible): the prior term
// is w ||N' L (p - p0)||^2. For a body whose a-priori values form a positive definite
// pseudo-inertia P0, its block is the second-order form of the log-det (Bregman) divergence of
// pseudo-inertias at P0 (Lee & Park, RA-L 2018; Lee, Wensing & Park, T-RO 2020):
// ||L_b dp||^2 = tr(P0^-1 dP P0^-1 dP), dP the pseudo-inertia of dp: the change measured
// relative to the body's own mass distribution, the same for every frame. Every other parameter
// gets 1 / scale.
Eigen::MatrixXd prior_metric_root(const Layout& layout, const Eigen::VectorXd& prior_value,
                                  const std::vector<char>& has_a_priori,
                                  const Eigen::VectorXd& scale);

// An orthonormal basis (columns) of the null space of K M: the directions (in the coordinates
// of M's inverse) that change no base parameter. The rank is decided relative to the largest
// singular value (1e-10), as the regrouping of rounding-level coefficients would otherwise
// count as information.
Eigen::MatrixXd null_space_of(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M);

// null_space_of(K, diag(scale)).
Eigen::MatrixXd scaled_null_space(const Eigen::MatrixXd& K, const Eigen::VectorXd& scale);

}  // namespace modelgen::detail
