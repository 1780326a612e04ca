// Per link, what a physically consistent fit says of its mass distribution beside the a-priori
// model: mass, centre of mass and principal moments of inertia about it, identified and
// a-priori, whether the data or the prior decided each, and a warning when the link moved far
// from its a-priori values.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/estimation/physical.hpp"
#include "modelgen/model/rigid_body_tree.hpp"
#include "modelgen/model/robot_model.hpp"

namespace modelgen {

/// A body's mass distribution for people (SI units, body frame).
struct LinkQuantities {
  double mass = 0;
  std::array<double, 3> com{};                ///< centre of mass
  std::array<double, 3> principal_moments{};  ///< of the inertia about the com, ascending
  std::array<double, 6> inertia_com{};        ///< xx, xy, xz, yy, yz, zz (tensor entries)
};

/// Who set a quantity: the data (its direction in the standard parameters lies, within 1 % of
/// its length in the prior's scaled metric, in the row space of the regrouping map, so every
/// standard set with the same base parameters has the same value), or the prior (the data leave
/// part of it free, and the prior term, bounded by consistency, chose), or the bound (the data
/// leave part of it free and the body's region from the geometry holds at the optimum: the
/// region, not the data or the prior, set it).
enum class DecidedBy { kData, kPrior, kBound };

const char* decided_by_name(DecidedBy by);  ///< "data", "prior", "bound"

struct LinkSummary {
  std::string body;
  LinkQuantities identified;
  std::optional<LinkQuantities> a_priori;  ///< when the description gives all ten values
  DecidedBy mass_by = DecidedBy::kPrior, com_by = DecidedBy::kPrior, moments_by = DecidedBy::kPrior;
  /// Why the link is far from its a-priori values (mass off by more than a factor 2, centre of
  /// mass more than 0.1 m away), e.g. "mass 2.60 x its a-priori value"; empty when it is not.
  std::vector<std::string> far_from_a_priori;
  /// The base parameters this link enters in which the data reject its a-priori values (more
  /// than kRejectingSd standard deviations), largest first, at most three, e.g. "MY5R -14.6 sd"
  /// (a_priori_disagreement.hpp); filled by the caller that has the unconstrained estimate.
  std::vector<std::string> a_priori_rejected_in;
  /// With a region from the description's geometry (modelgen/model/robot_model.hpp), the
  /// link's extent in it (region_extent); above 1 the mass reaches outside the region.
  std::optional<double> region_extent;
  bool region_guessed = false;   ///< the region is a guess from the segments to the next joints
  bool region_at_joint = false;  ///< guessed as a sphere about the joint (no next joint or tool)
  bool region_rejected = false;  ///< guessed, and the data rejected it: not enforced
};

inline constexpr double kFarMassFactor = 2.0;
inline constexpr double kFarComDistance = 0.1;  // m
inline constexpr double kRejectingSd = 3.0;

/// A drive parameter (rotor inertia, friction, offset: every standard parameter outside the
/// bodies) of the consistent fit: identified only when the data decided it alone. One the
/// regrouping adds to others (Ia1 into ZZ1R about a vertical first axis) has its value from the
/// prior (or the start) and consistency, not from the data.
struct DriveSummary {
  std::string name;
  double identified = 0;
  std::optional<double> a_priori;
  DecidedBy by = DecidedBy::kPrior;
  /// The standard parameters it is regrouped with (sharing a base parameter), e.g. {"ZZ1"}.
  std::vector<std::string> regrouped_with;
};

/// One summary per drive parameter of `tree`, in tree.params order (arguments as for
/// summarise_links).
std::vector<DriveSummary> summarise_drives(const RigidBodyTree& tree, const Eigen::MatrixXd& K,
                                           const PhysicalFitResult& fit,
                                           const std::vector<std::optional<double>>& a_priori);

/// How far a body's mass distribution reaches in `region`, in units of the region: the root
/// mean square over the mass of sum_i ((x_i - centre_i) / semi_axes_i)^2. A distribution held
/// by the ellipsoid has at most 1; above 1, some of its mass lies outside. That is the
/// density-realizability condition on an ellipsoid (Wensing, Kim & Slotine, RA-L 2017):
/// tr(P Q) >= 0 with P the pseudo-inertia and Q the ellipsoid's matrix, here as
/// sqrt(1 - tr(P Q) / m). Infinite for a body without positive mass.
double region_extent(const double* p, const BodyRegion& region);

/// The quantities of one body's ten standard parameters (XX XY XZ YY YZ ZZ MX MY MZ M, inertia
/// about the body frame's origin); a body without positive mass keeps com and moments at 0.
LinkQuantities link_quantities(const double* p);

/// Why `identified` is far from `a_priori` (mass off by more than kFarMassFactor, centre of mass
/// further than kFarComDistance), in words; empty when it is not, or without an a-priori mass.
std::vector<std::string> far_from_a_priori(const LinkQuantities& identified,
                                           const LinkQuantities& a_priori);

/// One summary per complete body of `tree`. `K` the regrouping matrix, `fit` the consistent
/// fit (its standard set, prior scales and the bodies its regions hold: their quantities the
/// data leave free are decided by the bound), `a_priori` the description's known values.
/// `regions` per tree.bodies entry (RobotModel::body_regions; may be shorter or empty).
std::vector<LinkSummary> summarise_links(
    const RigidBodyTree& tree, const Eigen::MatrixXd& K, const PhysicalFitResult& fit,
    const std::vector<std::optional<double>>& a_priori,
    const std::vector<std::optional<BodyRegion>>& regions = {});

}  // namespace modelgen
