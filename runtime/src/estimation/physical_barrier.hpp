// The barrier method of the physically consistent fit (physical.cpp): the optimiser's variables
// (per complete body the ten distinct entries of its pseudo-inertia, every other standard
// parameter as itself), the projection onto the consistent set, and min 1/2 y'Hy - h'y over that
// set by Newton steps on the log det barrier (Boyd & Vandenberghe, Convex Optimization, section
// 11.3). A body with a region from the description's geometry also keeps tr(P Q) > 0, Q the
// region's ellipsoid matrix (Wensing, Kim & Slotine, RA-L 2017): its mass inside the
// ellipsoid in the root mean square, a log barrier on a linear function of the variables.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "modelgen/model/rigid_body_tree.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen::detail {

// Where each standard parameter lives among the optimiser's blocks.
struct Layout {
  std::vector<std::array<int, 10>> body_params;  // complete bodies: their ten standard indices
  std::vector<int> scalar_params;                // every other standard parameter
  /// Per complete body, its region if it has one, and the row r of tr(P Q) = r' x over the
  /// body's ten variables x (entries of P, off-diagonal ones times sqrt 2).
  std::vector<std::optional<BodyRegion>> region;
  std::vector<std::optional<std::array<double, 10>>> region_row;
};

Layout make_layout(const RigidBodyTree& tree);

/// The pseudo-inertia of a body's ten variables x (below: off-diagonal entries times sqrt 2),
/// and the basis E_e of that map: P = sum_e x_e E_e.
Eigen::Matrix4d pseudo_inertia_of_entries(const double* x);
const std::array<Eigen::Matrix4d, 10>& entry_basis();

/// Q of an ellipsoid (x - c)' A (x - c) <= 1, A = diag(semi_axes^-2): [x; 1]' Q [x; 1] =
/// 1 - (x - c)' A (x - c), so tr(P Q) = int 1 - (x - c)' A (x - c) dm.
Eigen::Matrix4d region_matrix(const BodyRegion& region);

/// Fills layout.region and region_row from `regions` (per tree.bodies entry; may be shorter or
/// empty).
void add_regions(const RigidBodyTree& tree, const std::vector<std::optional<BodyRegion>>& regions,
                 Layout& layout);

/// Moves each body of `x` whose tr(P Q) is not positive into its region: its mass distribution
/// (above the floor) shrunk towards the region's centre until its rms extent is at most 1/2, a
/// congruence P -> S P S' that keeps P positive definite.
void shrink_into_regions(const Layout& layout, const std::vector<double>& body_floor,
                         Eigen::VectorXd& x);

// The optimisation variables: per complete body the ten distinct entries of its pseudo-inertia
// (off-diagonal ones times sqrt 2, so that the Euclidean norm is the Frobenius norm and the
// projection onto the consistent set clips eigenvalues), stored in that body's ten standard
// slots; every other parameter as itself. Returns T, n x n: standard = T variables.
Eigen::MatrixXd standard_from_variables(const Layout& layout, Eigen::Index n);

// Projection onto the consistent set (in the variables, scaled per body by one factor, which
// leaves the cone unchanged): each pseudo-inertia's eigenvalues raised to at least its body's
// floor (strictly positive definite: a mass, and a log-Cholesky factor, for every body),
// bounded parameters to at least 0.
void project(const Layout& layout, const std::vector<char>& bounded,
             const std::vector<double>& body_floor, Eigen::VectorXd& x);

// One scale per body (its variables' largest column norm in A) and per scalar, so that the
// penalty rho weighs every block alike.
Eigen::VectorXd variable_scales(const Layout& layout, const Eigen::MatrixXd& A);

// min 1/2 y'Hy - h'y (+ a convex term) over the consistent set by the barrier method (Boyd &
// Vandenberghe, Convex Optimization, algorithm 11.1: Newton's method with backtracking on t f +
// barrier, t growing tenfold, until the duality gap m / t is negligible).
struct BarrierOutcome {
  Eigen::VectorXd y;
  Eigen::VectorXd push;  // per variable, how hard its cone or bound pushes at the end (duals)
  // Per complete body, how hard its region pushes each of its variables at the end (the
  // largest entry of the dual times r; 0 without a region).
  std::vector<double> region_push;
  int iterations = 0;
  bool converged = false;
};

/// A convex term added to the quadratic: its value at y into `value` (added), and, given
/// `gradient`, its gradient and Hessian added to them; false where y is outside its domain.
/// Called only at points strictly inside the consistent set.
using ConvexTerm = std::function<bool(const Eigen::VectorXd& y, double& value,
                                      Eigen::VectorXd* gradient, Eigen::MatrixXd* hessian)>;

/// min 1/2 y'Hy - h'y + extra(y) over the consistent set (`extra` may be empty), until the
/// duality gap is below 1e-13 of the problem's size and, given the convex term's weight w
/// (`extra_weight` > 0), below 1e-9 w: a weak convex term is resolved only when the barrier's
/// own pull, 1/t, is far below it (else the central path's point lies off in the directions
/// only that term decides). With w, t starts at 1e-6 / w at the least (physical_barrier.cpp).
BarrierOutcome minimise_on_consistent_set(const Eigen::MatrixXd& H, const Eigen::VectorXd& h,
                                          const Layout& layout, const std::vector<char>& bounded,
                                          const std::vector<double>& body_floor, Eigen::VectorXd y,
                                          int max_iterations, const ConvexTerm& extra = {},
                                          double extra_weight = 0);

}  // namespace modelgen::detail
