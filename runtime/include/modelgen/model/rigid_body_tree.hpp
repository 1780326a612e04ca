// The internal robot model every part of modelgen computes on: a tree of bodies, each attached
// to its antecedent by a constant transform followed by one joint motion, and the ordered list of
// standard dynamic parameters (Gautier & Briot eq. 3). MDH and URDF descriptions both become this.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace modelgen {

enum class JointType { kRevolute, kPrismatic, kFixed };

/// A rigid transform: `rotation` row-major 3x3, `translation` in metres.
/// Maps coordinates in the child frame to the parent frame: x_parent = R x_child + t.
struct Frame {
  std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::array<double, 3> translation{0, 0, 0};
};

/// One body (link) and the joint that carries it.
/// Frame j is reached from the antecedent's frame by `fixed` then the joint motion: a rotation
/// by q about `axis` (revolute) or a translation by q along `axis` (prismatic), `axis` being a unit
/// vector in frame j. For MDH, `fixed` = Rot_x(alpha) Trans_x(d) Rot_z(theta) Trans_z(r) at q = 0
/// and `axis` = z.
struct Body {
  std::string name;
  int parent = -1;  ///< index into RigidBodyTree::bodies, -1 for the base; parents come first
  JointType type = JointType::kRevolute;
  int dof_index = -1;  ///< index into q for moving joints, -1 for fixed ones
  Frame fixed;
  std::array<double, 3> axis{0, 0, 1};
};

/// What a standard parameter is. Inertial ones are about the origin of the body frame, in the
/// body frame; XY etc. are tensor entries (XY = -integral of x y dm).
enum class ParamKind {
  kXX,
  kXY,
  kXZ,
  kYY,
  kYZ,
  kZZ,  // inertia tensor, kg m^2
  kMX,
  kMY,
  kMZ,  // first moments, kg m
  kM,   // mass, kg
  kIa,  // drive (rotor + gear) inertia on the joint side
  kFv,
  kFc,   // viscous and Coulomb friction
  kOff,  // torque offset
  kFvPos,
  kFvNeg,
  kFcPos,
  kFcNeg,  // asymmetric friction (Bona & Curatella eq. 2)
  kIam,
  kFvm,
  kFcm  // rotor inertia and friction of a motor that drives several
        // joints (Gautier & Briot eq. 26), see CoupledMotor
};

struct StandardParam {
  std::string name;  ///< e.g. "XX1", "Ia3", "Fcp2"
  int body = -1;     ///< index into RigidBodyTree::bodies
  ParamKind kind = ParamKind::kM;
};

/// A motor whose velocity is a combination of several joint velocities (a coupled wrist):
/// dq_motor = ratio * sum_l coupling[l] dq[l], with coupling[dof_index] = 1. Its rotor inertia
/// and friction, scaled to its own joint (Iam = ratio^2 J_rotor, Fvm = ratio^2 Fv_rotor,
/// Fcm = ratio Fc_rotor), add tau[l] += coupling[l] (Iam u'' + Fvm u' + Fcm sign(u')) with
/// u' = sum_l coupling[l] dq[l] (Gautier & Briot eq. 26; Swevers et al. eq. 5-10).
struct CoupledMotor {
  int dof_index = -1;            ///< the joint this motor is numbered after
  std::vector<double> coupling;  ///< one entry per dof
};

struct RigidBodyTree {
  std::vector<Body> bodies;
  std::array<double, 3> gravity{0, 0, -9.81};  ///< in the base frame, m/s^2
  int dof = 0;                                 ///< number of moving joints
  std::vector<StandardParam> params;           ///< order of the standard parameter vector
  std::vector<CoupledMotor> coupled_motors;    ///< motors kIam/kFvm/kFcm parameters refer to
  /// How precisely the description fixes the geometry's angles, rad (the loader's
  /// --angle-tolerance; 0 = exact). Base-parameter rank decisions ignore effects of this size.
  double angle_precision = 0;
};

/// The coupled motor a kIam/kFvm/kFcm parameter belongs to: the one numbered after the joint of
/// the parameter's body. nullptr if there is none.
const CoupledMotor* coupled_motor_of(const RigidBodyTree& tree, const StandardParam& param);

/// The name stem of a parameter kind: "XX", "Ia", "Fcp", ...
const char* param_kind_stem(ParamKind kind);

/// Whether a parameter kind is one of the ten inertial parameters of a body (XX..ZZ, MX..MZ, M),
/// as opposed to a drive, friction or offset parameter.
bool is_inertial(ParamKind kind);

/// Checks the invariants the dynamics rely on: parents before children, dof indices 0..dof-1
/// once each, unit axes, orthonormal rotations, parameters on existing bodies, no duplicate
/// parameter, drive parameters only on moving joints. Throws std::invalid_argument naming the
/// body or parameter at fault.
void validate(const RigidBodyTree& tree);

}  // namespace modelgen
