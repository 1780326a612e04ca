// The standard deviations of the physically consistent fit's base estimate (physical.cpp).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "runtime/src/estimation/physical_barrier.hpp"

namespace modelgen::detail {

// Standard deviations of the constrained base estimate. Without a binding constraint they are
// the unconstrained ones (diagonal of the inverse information). Otherwise the free directions
// at the optimum are the log-Cholesky parameters of the bodies not bound and the parameters
// not on a binding bound, and the covariance of the free ones (a pseudo-inverse: the data leave
// standard directions free) is carried to beta. Holding the rest would give them no spread (sd
// 0 on the boundary), which is not so: the estimate leaves the boundary whenever the data pull
// it inside. Their part is the unconstrained covariance's component F-orthogonal to the free
// directions, (I - P) F^-1 (I - P)', P the F-orthogonal projector onto the free base
// directions (F^-1 splits into the two parts exactly). That is an upper bound: a scalar
// estimate clipped at a bound its truth lies on has sd sqrt(1/2 - 1/(2 pi)) = 0.58 of the
// unconstrained one, one whose truth is well inside the unconstrained sd; the local
// covariance of the active set alone says 0 for both.
// G: the root of the prior term's Hessian in the variables (G'G), U: of the information, T
// and d: standard = T variables / d.
Eigen::VectorXd base_standard_deviations(const Layout& layout, const std::vector<char>& binding,
                                         const Eigen::MatrixXd& K, const Eigen::MatrixXd& U,
                                         const Eigen::MatrixXd& G, const Eigen::MatrixXd& T,
                                         const Eigen::VectorXd& d, const Eigen::VectorXd& standard);

}  // namespace modelgen::detail
