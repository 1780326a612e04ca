// Whether a standard parameter vector is that of a physical robot: per body a mass
// distribution that exists (mass > 0, inertia about the centre of mass positive semidefinite
// with the triangle inequalities: the pseudo-inertia of modelgen/model/pseudo_inertia.hpp
// positive semidefinite), rotor inertias and friction coefficients not negative.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "modelgen/model/rigid_body_tree.hpp"

namespace modelgen {

/// One condition a parameter vector breaks.
struct PhysicalViolation {
  int body = -1;          ///< index into RigidBodyTree::bodies
  std::string parameter;  ///< the standard parameter at fault, e.g. "M2", "XX4", "Fv3"
  std::string condition;  ///< what is wrong, with the numbers, e.g. "mass -1 is not positive"
};

/// The conditions `standard` (one value per tree.params entry) breaks. A body is judged only
/// when all ten of its inertial parameters are in tree.params; an all-zero body (massless) is
/// consistent. The inertial conditions hold with equality for thin rods and point masses; they
/// are accepted to `relative_tolerance` of the body's inertia scale, so rounding in a
/// description does not become a violation. Drive parameters must be >= 0 exactly. Fcm is not
/// judged: its sign is the gear ratio's (CoupledMotor). Throws std::invalid_argument on a size
/// mismatch.
std::vector<PhysicalViolation> physical_violations(const RigidBodyTree& tree,
                                                   const Eigen::VectorXd& standard,
                                                   double relative_tolerance = 1e-9);

/// Whether a drive parameter kind is a magnitude that cannot be negative: rotor inertias
/// (Ia, Iam) and friction coefficients (Fv, Fc, Fvp, Fvn, Fcp, Fcn, Fvm; the negative side's
/// Coulomb term enters with a minus sign, Bona & Curatella eq. 2). Not Fcm, not offsets.
bool must_be_nonnegative(ParamKind kind);

/// Each body's ten inertial parameters as positions into tree.params, in ParamKind order
/// (XX, XY, XZ, YY, YZ, ZZ, MX, MY, MZ, M); -1 where the tree has no such parameter.
std::vector<std::array<int, 10>> inertial_param_indices(const RigidBodyTree& tree);

}  // namespace modelgen
